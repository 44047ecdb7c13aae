!> F77-callable face of forward-symplectic: external (non-module) subroutines with
!> explicit-shape arrays, an integer method id, caller-provided work arrays and an integer
!> status. They run the one splitting kernel (`fsym_kernel`), so they give the same numbers
!> as `integrator_t`, bit for bit. Nothing here stops, allocates or does I/O.
!>
!> Work arrays: `RW(LRW)` (double precision) and `IW(LIW)` (integer) hold the scheme table,
!> the kernel state and the kernel's slots (layout in `fsym_legacy_work`); `FSYMWK` gives
!> their lengths, `FSYMIN` fills them. The caller must not change them between calls.
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
    use fsym_legacy_work, only: legacy_sizes, legacy_store, LEGACY_MAGIC, LEGACY_KO, LEGACY_KC
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_WORK_SIZE
    use fsym_kinds, only: wp
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    use fsym_kernel, only: kernel_state_t, fsym_kernel_layout
    implicit none
    integer, intent(in) :: METH          !! method id (FSYMID)
    integer, intent(in) :: ND, N         !! dimensions, bodies
    integer, intent(in) :: LRW, LIW      !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)   !! real work array
    integer, intent(inout) :: IW(LIW)    !! integer work array
    integer, intent(out) :: INFO         !! status
    type(scheme_t) :: s
    type(kernel_state_t) :: ks
    character(len=FSYM_NAME_LEN), allocatable :: cat(:)
    integer :: need_r, need_i
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
    call fsym_kernel_layout(s%op, .false., ND, N, ks)
    call legacy_store(ks, IW(8:LEGACY_KO - 1), RW(1:4))
    IW(1) = LEGACY_MAGIC
    IW(2) = ND; IW(3) = N; IW(4) = s%nop; IW(5) = ks%nslot; IW(6) = METH; IW(7) = 0
    IW(LEGACY_KO:LEGACY_KO + s%nop - 1) = s%op
    RW(LEGACY_KC:LEGACY_KC + s%nop - 1) = s%c
    RW(LEGACY_KC + s%nop:LEGACY_KC + 2 * s%nop - 1) = s%u
    INFO = FSYM_SUCCESS
end subroutine FSYMIN

!> NSTEP steps of size H of the method set up by FSYMIN on X(ND,N), V(ND,N), with the
!> caller's acceleration routine `ACCEL(ND, N, X, A)` and, for methods with a gradient
!> kick (A, C, AN), the gradient term routine `GRAD(ND, N, X, A, G)` (any routine with that
!> signature may be passed for the other methods; it is not called). On failure (INFO /= 0)
!> X and V hold the state after the last completed step; IW(7) tells how many were done.
subroutine FSYMST(ND, N, X, V, H, NSTEP, ACCEL, GRAD, RW, LRW, IW, LIW, INFO)
    use fsym_status, only: FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_BAD_REQUEST
    use fsym_kinds, only: wp, ik
    use fsym_kernel, only: kernel_state_t, fsym_kernel_run
    use fsym_legacy_work, only: legacy_ok, legacy_load, legacy_store, legacy_model_t, &
                                LEGACY_KO, LEGACY_KC
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
    type(kernel_state_t) :: ks
    type(legacy_model_t) :: model
    integer :: nop, kw
    integer(ik) :: ndone
    if (.not. legacy_ok(ND, N, LRW, LIW, IW)) then
        ! IW may be shorter than 7 here: write nothing into it
        INFO = FSYM_ERR_NOT_INITIALIZED
        return
    end if
    IW(7) = 0
    call legacy_load(IW(8:LEGACY_KO - 1), RW(1:4), ks)
    if (ks%active) then
        INFO = FSYM_ERR_BAD_REQUEST; return     ! a reverse-communication step is open
    end if
    nop = IW(4)
    kw = LEGACY_KC + 2 * nop
    model%accel => ACCEL
    model%grad => GRAD
    call fsym_kernel_run(IW(LEGACY_KO:LEGACY_KO + nop - 1), RW(LEGACY_KC:LEGACY_KC + nop - 1), &
                         RW(LEGACY_KC + nop:kw - 1), model, ks, X, V, RW(kw), H, &
                         int(NSTEP, ik), ndone, INFO)
    IW(7) = int(ndone)
    call legacy_store(ks, IW(8:LEGACY_KO - 1), RW(1:4))
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
!> (X, V restored). Do not change X or V while a step is in progress. It runs the kernel of
!> FSYMST stage by stage: the kernel suspends where FSYMST would call ACCEL or GRAD.
subroutine FSYMRC(ND, N, X, V, H, RW, LRW, IW, LIW, IREQ, IPNT, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_NOT_INITIALIZED, FSYM_ERR_BAD_REQUEST
    use fsym_kinds, only: wp, ik
    use fsym_kernel, only: kernel_state_t, fsym_kernel_run, fsym_kernel_abort, &
                           KERNEL_SUSPEND, REQ_FORCE, REQ_GRADIENT, REQ_FORCE_SHIFTED
    use fsym_legacy_work, only: legacy_ok, legacy_load, legacy_store, suspend_model_t, &
                                LEGACY_KO, LEGACY_KC
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
    type(kernel_state_t) :: ks
    type(suspend_model_t) :: model
    integer :: nop, kw, m
    integer(ik) :: ndone
    IPNT = 0
    if (.not. legacy_ok(ND, N, LRW, LIW, IW)) then
        IREQ = -1; INFO = FSYM_ERR_NOT_INITIALIZED; return
    end if
    nop = IW(4)
    kw = LEGACY_KC + 2 * nop
    m = ND * N
    call legacy_load(IW(8:LEGACY_KO - 1), RW(1:4), ks)
    if (IREQ == -1) then
        call fsym_kernel_abort(ks, X, V, RW(kw))
        call legacy_store(ks, IW(8:LEGACY_KO - 1), RW(1:4))
        IREQ = 0; INFO = FSYM_SUCCESS; return
    end if
    if (ks%active .neqv. IREQ /= 0) then
        IREQ = -1; INFO = FSYM_ERR_BAD_REQUEST; return
    end if
    if (ks%active .and. IREQ /= ks%req) then
        IREQ = -1; INFO = FSYM_ERR_BAD_REQUEST; return
    end if
    call fsym_kernel_run(IW(LEGACY_KO:LEGACY_KO + nop - 1), RW(LEGACY_KC:LEGACY_KC + nop - 1), &
                         RW(LEGACY_KC + nop:kw - 1), model, ks, X, V, RW(kw), H, 1_ik, &
                         ndone, INFO)
    call legacy_store(ks, IW(8:LEGACY_KO - 1), RW(1:4))
    if (INFO == KERNEL_SUSPEND) then
        INFO = FSYM_SUCCESS
        IREQ = ks%req
        select case (ks%req)
        case (REQ_FORCE)
            IPNT(2) = kw + (ks%ia - 1) * m
        case (REQ_GRADIENT)
            IPNT(2) = kw + (ks%ig - 1) * m
            IPNT(3) = kw + (ks%ia - 1) * m
        case (REQ_FORCE_SHIFTED)
            IPNT(1) = kw + (ks%iqe - 1) * m
            IPNT(2) = kw + (ks%iae - 1) * m
        case default
            continue      ! no other request exists
        end select
    else if (INFO == FSYM_SUCCESS) then
        IREQ = 0
    else
        IREQ = -1
    end if
end subroutine FSYMRC

!> Force and gradient evaluations supplied since FSYMIN (FSYMST and FSYMRC together).
subroutine FSYMNF(RW, LRW, NF, NG)
    use fsym_kinds, only: wp
    implicit none
    integer, intent(in) :: LRW          !! length of RW
    real(wp), intent(in) :: RW(LRW)     !! work array set up by FSYMIN
    integer, intent(out) :: NF, NG      !! force and gradient evaluations
    NF = 0; NG = 0
    if (LRW < 4) return
    NF = nint(RW(3)); NG = nint(RW(4))
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
