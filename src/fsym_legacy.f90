!> F77-callable face of forward-symplectic: external (non-module) subroutines with
!> explicit-shape arrays, an integer method id, caller-provided work arrays and an integer
!> status. They drive the one splitting kernel (`fsym_kernel`), so they give the same numbers
!> as `integrator_t`, bit for bit. Nothing here stops, allocates or does I/O.
!>
!> Work arrays: `RW(LRW)` (double precision) and `IW(LIW)` (integer) hold the scheme table,
!> the kernel state and the kernel's slots; `FSYMWK` gives their lengths, `FSYMIN` fills them.
!> The caller must not change them between calls.
!>
!>     IW(1)  magic (initialised)        RW(1:KERNEL_NRW)   kernel real state
!>     IW(2)  ND   IW(3) N               RW(KERNEL_NRW+1)   force evaluations (counter)
!>     IW(4)  NOP  IW(5) NSLOT           RW(KERNEL_NRW+2)   gradient evaluations (counter)
!>     IW(6)  method id                  then C(NOP), U(NOP), then the slots W(ND,N,NSLOT)
!>     IW(7)  steps completed by the last FSYMST call
!>     IW(8:) kernel integer state (KERNEL_NIW), then the op codes (NOP)
!>
!> Status codes (INFO) are those of `fsym_status` (0 = success); `FSYMMS` gives the text.
!>
!> Entry points: FSYMID (id from a name), FSYMWK (work sizes), FSYMIN (set up), FSYMST (steps
!> with an EXTERNAL acceleration routine), FSYMRC (one step by reverse communication), FSYMNF
!> (evaluation counts), FSYMMS (status text), FSYMPK/FSYMUP (structure-of-arrays adapter).

!> Method id of a name: its index in `fsym_catalogue()` (1 = T2, 2 = FR, 3 = A, 4 = A', ...),
!> or 0 when the name is not a catalogue method. Case and the spelling of the prime are free
!> (`A'`, `a prime`).
subroutine FSYMID(NAME, METH)
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    implicit none
    character(len=*), intent(in) :: NAME   !! method label
    integer, intent(out) :: METH           !! catalogue index, 0 if unknown
    type(scheme_t) :: s
    character(len=FSYM_NAME_LEN), allocatable :: cat(:)
    character(len=256) :: msg
    integer :: st, k
    METH = 0
    call fsym_scheme_by_name(NAME, s, st, msg)
    if (st /= 0) return
    cat = fsym_catalogue()
    do k = 1, size(cat)
        if (trim(cat(k)) == s%name) then
            METH = k
            return
        end if
    end do
end subroutine FSYMID

!> Lengths of the work arrays for method METH on arrays X(ND,N): LRW reals, LIW integers.
subroutine FSYMWK(METH, ND, N, LRW, LIW, INFO)
    use fsym_legacy_work, only: legacy_sizes
    implicit none
    integer, intent(in) :: METH      !! method id (FSYMID)
    integer, intent(in) :: ND, N     !! dimensions, bodies
    integer, intent(out) :: LRW      !! reals needed
    integer, intent(out) :: LIW      !! integers needed
    integer, intent(out) :: INFO     !! status
    call legacy_sizes(METH, ND, N, LRW, LIW, INFO)
end subroutine FSYMWK

!> Set up the work arrays for method METH on X(ND,N). A work array shorter than FSYMWK's
!> answer is rejected with INFO = 10 (FSYM_ERR_WORK_SIZE) and nothing is written.
subroutine FSYMIN(METH, ND, N, RW, LRW, IW, LIW, INFO)
    use fsym_legacy_work, only: legacy_sizes, LEGACY_MAGIC
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_WORK_SIZE
    use fsym_kinds, only: wp
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue
    use fsym_kernel, only: fsym_kernel_layout, KERNEL_NIW, KERNEL_NRW
    implicit none
    integer, intent(in) :: METH          !! method id (FSYMID)
    integer, intent(in) :: ND, N         !! dimensions, bodies
    integer, intent(in) :: LRW, LIW      !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)   !! real work array
    integer, intent(inout) :: IW(LIW)    !! integer work array
    integer, intent(out) :: INFO         !! status
    type(scheme_t) :: s
    character(len=24), allocatable :: cat(:)
    integer :: need_r, need_i, nslot, ko, kc
    call legacy_sizes(METH, ND, N, need_r, need_i, INFO)
    if (INFO /= FSYM_SUCCESS) return
    if (LRW < need_r .or. LIW < need_i) then
        INFO = FSYM_ERR_WORK_SIZE; return
    end if
    cat = fsym_catalogue()
    call fsym_scheme_by_name(cat(METH), s, INFO)
    if (INFO /= FSYM_SUCCESS) return
    IW(1:need_i) = 0
    RW(1:need_r) = 0.0_wp
    call fsym_kernel_layout(s%op, .false., IW(8:7 + KERNEL_NIW), RW(1:KERNEL_NRW), nslot)
    IW(1) = LEGACY_MAGIC
    IW(2) = ND; IW(3) = N; IW(4) = s%nop; IW(5) = nslot; IW(6) = METH; IW(7) = 0
    ko = 8 + KERNEL_NIW
    IW(ko:ko + s%nop - 1) = s%op
    kc = KERNEL_NRW + 3
    RW(kc:kc + s%nop - 1) = s%c
    RW(kc + s%nop:kc + 2 * s%nop - 1) = s%u
    INFO = FSYM_SUCCESS
end subroutine FSYMIN

!> NSTEP steps of size H of the method set up by FSYMIN on X(ND,N), V(ND,N), with the
!> caller's acceleration routine `ACCEL(ND, N, X, A)` and, for methods with a gradient
!> kick (A, C, AN), the gradient term routine `GRAD(ND, N, X, A, G)` (any routine with that
!> signature may be passed for the other methods; it is not called). On failure (INFO /= 0)
!> X and V hold the state after the last completed step; IW(7) tells how many were done.
subroutine FSYMST(ND, N, X, V, H, NSTEP, ACCEL, GRAD, RW, LRW, IW, LIW, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_NOT_INITIALIZED
    use fsym_kinds, only: wp, ik
    use fsym_kernel, only: fsym_kernel_begin, fsym_kernel_resume, fsym_kernel_slot, &
                           KERNEL_NIW, KERNEL_NRW, SLOT_A, SLOT_G, SLOT_QE, SLOT_AE, &
                           REQ_FORCE, REQ_GRADIENT, REQ_FORCE_SHIFTED
    use fsym_legacy_work, only: legacy_ok
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(inout) :: X(ND, N)         !! positions
    real(wp), intent(inout) :: V(ND, N)         !! velocities
    real(wp), intent(in) :: H                   !! step
    integer, intent(in) :: NSTEP                !! number of steps
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)          !! work array set up by FSYMIN
    integer, intent(inout) :: IW(LIW)           !! work array set up by FSYMIN
    integer, intent(out) :: INFO                !! status
    procedure(fsym_legacy_accel) :: ACCEL       !! ACCEL(ND, N, X, A): accelerations at X
    procedure(fsym_legacy_grad) :: GRAD         !! GRAD(ND, N, X, A, G): gradient term at X
    integer :: nop, nslot, ko, kc, kw, m, istep, req, ia, ig, iqe, iae
    integer(ik) :: nf, ng
    logical :: ok
    ok = legacy_ok(ND, N, LRW, LIW, IW)
    if (.not. ok) then
        ! IW may be shorter than 7 here: write nothing into it
        INFO = FSYM_ERR_NOT_INITIALIZED
        return
    end if
    IW(7) = 0
    nop = IW(4); nslot = IW(5)
    ko = 8 + KERNEL_NIW; kc = KERNEL_NRW + 3; kw = kc + 2 * nop
    m = ND * N
    ia = kw + (fsym_kernel_slot(IW(8:), SLOT_A) - 1) * m
    ig = kw + (fsym_kernel_slot(IW(8:), SLOT_G) - 1) * m
    iqe = kw + (fsym_kernel_slot(IW(8:), SLOT_QE) - 1) * m
    iae = kw + (fsym_kernel_slot(IW(8:), SLOT_AE) - 1) * m
    nf = int(RW(KERNEL_NRW + 1), ik); ng = int(RW(KERNEL_NRW + 2), ik)
    INFO = FSYM_SUCCESS
    do istep = 1, NSTEP
        call fsym_kernel_begin(ND, N, X, V, H, RW(kw), nslot, IW(8), RW(1), INFO)
        if (INFO /= FSYM_SUCCESS) exit
        do
            call fsym_kernel_resume(nop, IW(ko), RW(kc), RW(kc + nop), ND, N, X, V, RW(kw), &
                                    nslot, IW(8), RW(1), nf, ng, req, INFO)
            select case (req)
            case (REQ_FORCE)
                call ACCEL(ND, N, X, RW(ia))
            case (REQ_GRADIENT)
                call GRAD(ND, N, X, RW(ia), RW(ig))
            case (REQ_FORCE_SHIFTED)
                call ACCEL(ND, N, RW(iqe), RW(iae))
            case default
                exit
            end select
        end do
        if (INFO /= FSYM_SUCCESS) exit
        IW(7) = istep
    end do
    RW(KERNEL_NRW + 1) = real(nf, wp); RW(KERNEL_NRW + 2) = real(ng, wp)
end subroutine FSYMST

!> One step of size H by reverse communication: the caller keeps its own force loop.
!> Call with IREQ = 0 to start a step. On return:
!>   IREQ = 0  the step is done (X, V advanced);
!>   IREQ = 1  store the accelerations at X in RW(IPNT(2)...), as an (ND,N) array;
!>   IREQ = 2  store the gradient term at X in RW(IPNT(2)...), given the accelerations at X
!>             in RW(IPNT(3)...);
!>   IREQ = 3  store the accelerations at the positions RW(IPNT(1)...) in RW(IPNT(2)...);
!>   IREQ = -1 failed, INFO says why, X and V are restored to the start of the step.
!> Then call again with IREQ unchanged. Call with IREQ = -1 to abandon a step in progress
!> (X, V restored). Do not change X or V while a step is in progress.
subroutine FSYMRC(ND, N, X, V, H, RW, LRW, IW, LIW, IREQ, IPNT, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_BAD_REQUEST
    use fsym_kinds, only: wp, ik
    use fsym_kernel, only: fsym_kernel_begin, fsym_kernel_resume, fsym_kernel_slot, &
                           fsym_kernel_abort, KERNEL_NIW, KERNEL_NRW, KW_ACTIVE, KW_REQ, &
                           SLOT_A, SLOT_G, SLOT_QE, SLOT_AE, REQ_DONE, REQ_ERROR, REQ_FORCE, &
                           REQ_GRADIENT, REQ_FORCE_SHIFTED
    use fsym_legacy_work, only: legacy_ok
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(inout) :: X(ND, N)         !! positions
    real(wp), intent(inout) :: V(ND, N)         !! velocities
    real(wp), intent(in) :: H                   !! step (read when a step starts)
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)          !! work array set up by FSYMIN
    integer, intent(inout) :: IW(LIW)           !! work array set up by FSYMIN
    integer, intent(inout) :: IREQ              !! request (see above)
    integer, intent(out) :: IPNT(3)             !! positions in RW of the request's arrays
    integer, intent(out) :: INFO                !! status
    integer :: nop, nslot, ko, kc, kw, m, req
    integer(ik) :: nf, ng
    logical :: ok
    IPNT = 0
    ok = legacy_ok(ND, N, LRW, LIW, IW)
    if (.not. ok) then
        IREQ = REQ_ERROR; INFO = FSYM_ERR_NOT_INITIALIZED; return
    end if
    nop = IW(4); nslot = IW(5)
    ko = 8 + KERNEL_NIW; kc = KERNEL_NRW + 3; kw = kc + 2 * nop
    m = ND * N
    if (IREQ == REQ_ERROR) then
        call fsym_kernel_abort(ND, N, X, V, RW(kw), nslot, IW(8))
        IREQ = REQ_DONE; INFO = FSYM_SUCCESS; return
    end if
    if (IREQ == REQ_DONE) then
        if (IW(7 + KW_ACTIVE) /= 0) then
            IREQ = REQ_ERROR; INFO = FSYM_ERR_BAD_REQUEST; return
        end if
        call fsym_kernel_begin(ND, N, X, V, H, RW(kw), nslot, IW(8), RW(1), INFO)
        if (INFO /= FSYM_SUCCESS) then
            IREQ = REQ_ERROR; return
        end if
    else if (IREQ /= IW(7 + KW_REQ) .or. IW(7 + KW_ACTIVE) == 0) then
        IREQ = REQ_ERROR; INFO = FSYM_ERR_BAD_REQUEST; return
    end if
    nf = int(RW(KERNEL_NRW + 1), ik); ng = int(RW(KERNEL_NRW + 2), ik)
    call fsym_kernel_resume(nop, IW(ko), RW(kc), RW(kc + nop), ND, N, X, V, RW(kw), nslot, &
                            IW(8), RW(1), nf, ng, req, INFO)
    RW(KERNEL_NRW + 1) = real(nf, wp); RW(KERNEL_NRW + 2) = real(ng, wp)
    IREQ = req
    select case (req)
    case (REQ_FORCE)
        IPNT(2) = kw + (fsym_kernel_slot(IW(8:), SLOT_A) - 1) * m
    case (REQ_GRADIENT)
        IPNT(2) = kw + (fsym_kernel_slot(IW(8:), SLOT_G) - 1) * m
        IPNT(3) = kw + (fsym_kernel_slot(IW(8:), SLOT_A) - 1) * m
    case (REQ_FORCE_SHIFTED)
        IPNT(1) = kw + (fsym_kernel_slot(IW(8:), SLOT_QE) - 1) * m
        IPNT(2) = kw + (fsym_kernel_slot(IW(8:), SLOT_AE) - 1) * m
    case default
        continue      ! REQ_DONE or REQ_ERROR: nothing to point at
    end select
end subroutine FSYMRC

!> Force and gradient evaluations supplied since FSYMIN (FSYMST and FSYMRC together).
subroutine FSYMNF(RW, LRW, NF, NG)
    use fsym_kinds, only: wp
    use fsym_kernel, only: KERNEL_NRW
    implicit none
    integer, intent(in) :: LRW          !! length of RW
    real(wp), intent(in) :: RW(LRW)     !! work array set up by FSYMIN
    integer, intent(out) :: NF, NG      !! force and gradient evaluations
    NF = 0; NG = 0
    if (LRW < KERNEL_NRW + 2) return
    NF = nint(RW(KERNEL_NRW + 1)); NG = nint(RW(KERNEL_NRW + 2))
end subroutine FSYMNF

!> Text of a status code INFO, blank-padded or cut to the length of MSG.
subroutine FSYMMS(INFO, MSG)
    use fsym_status, only: fsym_status_message
    implicit none
    integer, intent(in) :: INFO             !! status code
    character(len=*), intent(out) :: MSG    !! its text
    MSG = fsym_status_message(INFO)
end subroutine FSYMMS

!> Structure-of-arrays adapter: pack XH(N), YH(N), ZH(N) into X(3,N).
subroutine FSYMPK(N, XH, YH, ZH, X)
    use fsym_kinds, only: wp
    implicit none
    integer, intent(in) :: N                            !! bodies
    real(wp), intent(in) :: XH(N), YH(N), ZH(N)         !! components
    real(wp), intent(out) :: X(3, N)                    !! packed array
    X(1, :) = XH; X(2, :) = YH; X(3, :) = ZH
end subroutine FSYMPK

!> Structure-of-arrays adapter: unpack X(3,N) into XH(N), YH(N), ZH(N).
subroutine FSYMUP(N, X, XH, YH, ZH)
    use fsym_kinds, only: wp
    implicit none
    integer, intent(in) :: N                            !! bodies
    real(wp), intent(in) :: X(3, N)                     !! packed array
    real(wp), intent(out) :: XH(N), YH(N), ZH(N)        !! components
    XH = X(1, :); YH = X(2, :); ZH = X(3, :)
end subroutine FSYMUP
