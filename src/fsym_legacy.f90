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
!> Calling convention: default INTEGERs of 4 bytes and DOUBLE PRECISION of 8 bytes, passed
!> by reference (the usual F77 convention). A code compiled with -fdefault-integer-8 (-i8)
!> or -fdefault-real-8 without -fdefault-double-8 does not match it; FSYMCV detects this.
!>
!> Entry points: FSYMID (id from a name), FSYMWK (work sizes), FSYMIN (set up), FSYMWL and
!> FSYMIL (the same by label, for any label), FSYMST (steps with an EXTERNAL acceleration
!> routine; FSYMG0 as GRAD says "no gradient term"), FSYMRC (one step by reverse
!> communication), FSYMRS (forget the cached force), FSYMNF/FSYMNL (evaluation counts),
!> FSYMMS (status text), FSYMCV (calling-convention check), FSYMGD (FSYMST with the
!> step-size guard), FSYMPK/FSYMUP
!> (structure-of-arrays adapter).

!> Method id of a name: its index in `fsym_catalogue()` (1 = T2, 2 = FR, 3 = A, 4 = A', ...),
!> or 0 when the name is not a catalogue method. Case, the spelling of the prime (`A'`,
!> `a prime`) and of a parameter (`M2(-1/2)`, `m2(-0.5)`) are free: the name is matched by
!> its coefficient table. Labels outside the catalogue (`A7`, `M2(-0.3)`) have no id; set
!> them up by name with FSYMWL/FSYMIL.
subroutine FSYMID(NAME, METH)
    use fsym_kinds, only: fsym_same
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    implicit none
    character(len=*), intent(in) :: NAME   !! method label
    integer, intent(out) :: METH           !! catalogue index, 0 if unknown
    type(scheme_t) :: s, e
    character(len=FSYM_NAME_LEN), allocatable :: cat(:)
    character(len=256) :: msg
    integer :: st, k
    METH = 0
    call fsym_scheme_by_name(NAME, s, st, msg)
    if (st /= 0) return
    allocate (cat, source=fsym_catalogue())
    do k = 1, size(cat)
        call fsym_scheme_by_name(cat(k), e, st, msg)
        if (st /= 0) cycle
        if (e%nop /= s%nop) cycle
        if (all(e%op == s%op) .and. all(fsym_same(e%c, s%c)) .and. all(fsym_same(e%u, s%u))) then
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
    use fsym_legacy_work, only: legacy_sizes, legacy_setup
    use fsym_status, only: FSYM_SUCCESS
    use fsym_kinds, only: wp
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name, fsym_catalogue, FSYM_NAME_LEN
    implicit none
    integer, intent(in) :: METH          !! method id (FSYMID)
    integer, intent(in) :: ND, N         !! dimensions, bodies
    integer, intent(in) :: LRW, LIW      !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)   !! real work array
    integer, intent(inout) :: IW(LIW)    !! integer work array
    integer, intent(out) :: INFO         !! status
    type(scheme_t) :: s
    character(len=FSYM_NAME_LEN), allocatable :: cat(:)
    integer :: need_r, need_i
    call legacy_sizes(METH, ND, N, need_r, need_i, INFO)
    if (INFO /= FSYM_SUCCESS) return
    allocate (cat, source=fsym_catalogue())
    call fsym_scheme_by_name(cat(METH), s, INFO)
    if (INFO /= FSYM_SUCCESS) return
    call legacy_setup(s, METH, ND, N, RW, LRW, IW, LIW, INFO)
end subroutine FSYMIN

!> Lengths of the work arrays for the method labelled NAME (any label `fsym_scheme_by_name`
!> reads: `A7`, `M2(-0.3)`, `A6'`, ...) on arrays X(ND,N). INFO as FSYMWK, and
!> FSYM_ERR_UNKNOWN_METHOD / FSYM_ERR_BAD_PARAMETER for a label that cannot be read.
subroutine FSYMWL(NAME, ND, N, LRW, LIW, INFO)
    use fsym_legacy_work, only: legacy_scheme_sizes
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name
    implicit none
    character(len=*), intent(in) :: NAME   !! method label
    integer, intent(in) :: ND, N           !! dimensions, bodies
    integer, intent(out) :: LRW            !! reals needed
    integer, intent(out) :: LIW            !! integers needed
    integer, intent(out) :: INFO           !! status
    type(scheme_t) :: s
    character(len=256) :: msg
    LRW = 0; LIW = 0
    call fsym_scheme_by_name(NAME, s, INFO, msg)
    if (INFO /= 0) return
    call legacy_scheme_sizes(s, ND, N, LRW, LIW, INFO)
end subroutine FSYMWL

!> Set up the work arrays for the method labelled NAME (as FSYMWL) on X(ND,N); then use
!> FSYMST and FSYMRC as after FSYMIN. Short work arrays: INFO = 10, nothing written.
subroutine FSYMIL(NAME, ND, N, RW, LRW, IW, LIW, INFO)
    use fsym_legacy_work, only: legacy_setup
    use fsym_legacy_api, only: FSYMID
    use fsym_scheme, only: scheme_t
    use fsym_paper_schemes, only: fsym_scheme_by_name
    use fsym_kinds, only: wp
    implicit none
    character(len=*), intent(in) :: NAME   !! method label
    integer, intent(in) :: ND, N           !! dimensions, bodies
    integer, intent(in) :: LRW, LIW        !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)     !! real work array
    integer, intent(inout) :: IW(LIW)      !! integer work array
    integer, intent(out) :: INFO           !! status
    type(scheme_t) :: s
    character(len=256) :: msg
    integer :: meth
    call fsym_scheme_by_name(NAME, s, INFO, msg)
    if (INFO /= 0) return
    call FSYMID(NAME, meth)
    call legacy_setup(s, meth, ND, N, RW, LRW, IW, LIW, INFO)
end subroutine FSYMIL

!> NSTEP steps of size H of the method set up by FSYMIN on X(ND,N), V(ND,N), with the
!> caller's acceleration routine `ACCEL(ND, N, X, A)` and, for methods with a gradient
!> kick (A, C, AN), the gradient term routine `GRAD(ND, N, X, A, G)`. A caller without a
!> gradient term passes the library's FSYMG0 as GRAD: a method with a gradient kick is then
!> refused (INFO = 8, FSYM_ERR_NO_GRADIENT; use the extrapolated form A', C', AN'), never
!> run with a wrong gradient. On failure (INFO /= 0) X and V hold the state after the last
!> completed step; IW(7) tells how many were done. NSTEP <= 0 is refused (INFO = 19).
!> INFO = 9: RW/IW not set up by FSYMIN; 7: set up for other ND, N; 10: LRW or LIW short.
subroutine FSYMST(ND, N, X, V, H, NSTEP, ACCEL, GRAD, RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_work, only: legacy_model_t, legacy_steps
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad, FSYMG0
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
    type(legacy_model_t) :: model
    model%accel => ACCEL
    model%grad => GRAD
    if (associated(model%grad, FSYMG0)) model%grad => null()
    call legacy_steps(ND, N, X, V, H, NSTEP, model, RW, LRW, IW, LIW, INFO)
end subroutine FSYMST

!> FSYMST with the step-size guard (as `integrator_t%set_guard`): the caller's routine
!> `FREQ(ND, N, X, W2, R)` gives the largest local omega^2 at X and the distance R where it
!> occurs (e.g. 2 G (m_i + m_j) / r_ij^3 over the pairs). Every step is checked at its start,
!> at every drift (end point and chord) and at its end against FRAC x* (x*: the method's
!> stability limit, kept in IW by FSYMIN; FRAC <= 0 means 1); a step beyond it is refused
!> with INFO = 20 (FSYM_ERR_STEP_TOO_LARGE), X and V those of the last step taken (IW(7)
!> of them). Otherwise as FSYMST.
subroutine FSYMGD(ND, N, X, V, H, NSTEP, ACCEL, GRAD, FREQ, FRAC, RW, LRW, IW, LIW, INFO)
    use fsym_kinds, only: wp
    use fsym_legacy_work, only: legacy_model_t, legacy_steps
    use fsym_legacy_api, only: fsym_legacy_accel, fsym_legacy_grad, fsym_legacy_freq, FSYMG0
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(inout) :: X(ND, N)         !! positions
    real(wp), intent(inout) :: V(ND, N)         !! velocities
    real(wp), intent(in) :: H                   !! step
    integer, intent(in) :: NSTEP                !! number of steps
    real(wp), intent(in) :: FRAC                !! fraction of x* (<= 0: 1)
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)          !! work array set up by FSYMIN
    integer, intent(inout) :: IW(LIW)           !! work array set up by FSYMIN
    integer, intent(out) :: INFO                !! status
    procedure(fsym_legacy_accel) :: ACCEL       !! ACCEL(ND, N, X, A): accelerations at X
    procedure(fsym_legacy_grad) :: GRAD         !! GRAD(ND, N, X, A, G), or FSYMG0
    procedure(fsym_legacy_freq) :: FREQ         !! FREQ(ND, N, X, W2, R): local frequency
    type(legacy_model_t) :: model
    model%accel => ACCEL
    model%grad => GRAD
    model%freq => FREQ
    if (associated(model%grad, FSYMG0)) model%grad => null()
    call legacy_steps(ND, N, X, V, H, NSTEP, model, RW, LRW, IW, LIW, INFO, FRAC)
end subroutine FSYMGD

!> The "no gradient term" routine: pass it as GRAD to FSYMST when the model has none (a
!> method with a gradient kick is then refused instead of run with a wrong gradient). It is
!> never called by the library; if called, it returns G = 0.
subroutine FSYMG0(ND, N, X, A, G)
    use fsym_kinds, only: wp
    implicit none
    integer, intent(in) :: ND, N                  !! dimensions, bodies
    real(wp), intent(in) :: X(ND, N), A(ND, N)    !! positions, accelerations
    real(wp), intent(out) :: G(ND, N)             !! set to zero
    associate (unused_x => X, unused_a => A); end associate   ! GRAD's arguments
    G = 0.0_wp
end subroutine FSYMG0

!> One step of size H by reverse communication: the caller keeps its own force loop.
!> Call with IREQ = 0 to start a step. On return:
!>   IREQ = 0  the step is done (X, V advanced);
!>   IREQ = 1  store the accelerations at X in RW(IPNT(2)...), as an (ND,N) array;
!>   IREQ = 2  store the gradient term at X in RW(IPNT(2)...), given the accelerations at X
!>             in RW(IPNT(3)...);
!>   IREQ = 3  store the accelerations at the positions RW(IPNT(1)...) in RW(IPNT(2)...);
!>   IREQ = -1 failed, INFO says why, X and V are restored to the start of the step.
!> Then call again with IREQ unchanged. Call with IREQ = -1 to abandon a step in progress
!> (X, V restored). Do not change X or V while a step is in progress. A call with another
!> IREQ than the one returned (or IREQ /= 0 with no step in progress) is refused with
!> IREQ = -1, INFO = 17, and the step in progress is abandoned: X and V are restored and
!> the next call with IREQ = 0 starts a new step. INFO = 9, 7, 10 as for FSYMST. It runs the
!> kernel of FSYMST stage by stage: the kernel suspends where FSYMST would call ACCEL or GRAD.
subroutine FSYMRC(ND, N, X, V, H, RW, LRW, IW, LIW, IREQ, IPNT, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_REQUEST, FSYM_ERR_BAD_ARGUMENT
    use fsym_integrator, only: fsym_overlap
    use fsym_kinds, only: wp, ik
    use fsym_kernel, only: kernel_state_t, fsym_kernel_run, fsym_kernel_abort, &
                           fsym_kernel_request, KERNEL_SUSPEND, KERNEL_NPACK, REQ_NONE
    use fsym_legacy_work, only: legacy_check, legacy_load, legacy_store, legacy_model_t, &
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
    type(legacy_model_t) :: model      ! never called: the kernel asks the caller
    integer :: nop, kw, m, req, at, into, given
    integer(ik) :: ndone
    IPNT = 0
    INFO = legacy_check(ND, N, LRW, LIW, IW, RW)
    if (INFO == FSYM_SUCCESS .and. fsym_overlap(X, V)) INFO = FSYM_ERR_BAD_ARGUMENT
    if (INFO /= FSYM_SUCCESS) then
        IREQ = -1; return
    end if
    nop = IW(4)
    kw = LEGACY_KC + 2 * nop
    m = ND * N
    call legacy_load(LIW, IW, RW(1:KERNEL_NPACK), ks, INFO)
    if (INFO /= FSYM_SUCCESS) then
        IREQ = -1; return
    end if
    if (IREQ == -1) then
        call fsym_kernel_abort(ks, X, V, RW(kw))
        call legacy_store(ks, RW(1:KERNEL_NPACK))
        IREQ = 0; INFO = FSYM_SUCCESS; return
    end if
    call fsym_kernel_request(ks, req, at, into, given)
    if ((req /= REQ_NONE .neqv. IREQ /= 0) .or. (req /= REQ_NONE .and. IREQ /= req)) then
        ! out of order: abandon the step in progress (X, V restored), then refuse
        call fsym_kernel_abort(ks, X, V, RW(kw))
        call legacy_store(ks, RW(1:KERNEL_NPACK))
        IREQ = -1; INFO = FSYM_ERR_BAD_REQUEST; return
    end if
    call fsym_kernel_run(nop, IW(LEGACY_KO:LEGACY_KO + nop - 1), &
                         RW(LEGACY_KC:LEGACY_KC + nop - 1), RW(LEGACY_KC + nop:kw - 1), &
                         model, ks, X, V, RW(kw), H, 1_ik, ndone, INFO, ask=.true.)
    call legacy_store(ks, RW(1:KERNEL_NPACK))
    if (INFO == KERNEL_SUSPEND) then
        INFO = FSYM_SUCCESS
        call fsym_kernel_request(ks, IREQ, at, into, given)
        ! the slots of the request as positions in RW (0: X itself, or none)
        if (at > 0) IPNT(1) = kw + (at - 1) * m
        if (into > 0) IPNT(2) = kw + (into - 1) * m
        if (given > 0) IPNT(3) = kw + (given - 1) * m
    else if (INFO == FSYM_SUCCESS) then
        IREQ = 0
    else
        IREQ = -1
    end if
end subroutine FSYMRC

!> Force and gradient evaluations supplied since FSYMIN (FSYMST and FSYMRC together). A count
!> beyond a default integer is returned as -1 (FSYMNL gives the 64-bit counts).
subroutine FSYMNF(RW, LRW, NF, NG)
    use fsym_kinds, only: wp, ik
    use fsym_legacy_api, only: FSYMNL
    implicit none
    integer, intent(in) :: LRW          !! length of RW
    real(wp), intent(in) :: RW(LRW)     !! work array set up by FSYMIN
    integer, intent(out) :: NF, NG      !! force and gradient evaluations (-1: too many)
    integer(ik) :: nf8, ng8
    call FSYMNL(RW, LRW, nf8, ng8)
    NF = -1; NG = -1
    if (nf8 <= huge(NF)) NF = int(nf8)
    if (ng8 <= huge(NG)) NG = int(ng8)
end subroutine FSYMNF

!> Force and gradient evaluations since FSYMIN as 64-bit integers (INTEGER*8).
subroutine FSYMNL(RW, LRW, NF, NG)
    use fsym_kinds, only: wp, ik
    implicit none
    integer, intent(in) :: LRW          !! length of RW
    real(wp), intent(in) :: RW(LRW)     !! work array set up by FSYMIN
    integer(ik), intent(out) :: NF, NG  !! force and gradient evaluations
    NF = 0; NG = 0
    if (LRW < 4) return
    ! the counts are kept as doubles: exact integers up to 2**53
    if (RW(3) >= 0.0_wp .and. RW(3) < 2.0_wp**62) NF = int(RW(3), ik)
    if (RW(4) >= 0.0_wp .and. RW(4) < 2.0_wp**62) NG = int(RW(4), ik)
end subroutine FSYMNL

!> Forget the cached force (call it after changing the force model's parameters, e.g. a
!> mass, between calls of FSYMST or FSYMRC; not needed after changing X, which is detected).
!> A reverse-communication step in progress is abandoned (X, V restored). INFO as FSYMST.
subroutine FSYMRS(ND, N, X, V, RW, LRW, IW, LIW, INFO)
    use fsym_status, only: FSYM_SUCCESS
    use fsym_kinds, only: wp
    use fsym_kernel, only: kernel_state_t, fsym_kernel_abort
    use fsym_kernel, only: KERNEL_NPACK
    use fsym_legacy_work, only: legacy_check, legacy_load, legacy_store, LEGACY_KC
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(inout) :: X(ND, N)         !! positions (restored if a step was open)
    real(wp), intent(inout) :: V(ND, N)         !! velocities (restored if a step was open)
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)          !! work array set up by FSYMIN
    integer, intent(inout) :: IW(LIW)           !! work array set up by FSYMIN
    integer, intent(out) :: INFO                !! status
    type(kernel_state_t) :: ks
    INFO = legacy_check(ND, N, LRW, LIW, IW, RW)
    if (INFO /= FSYM_SUCCESS) return
    call legacy_load(LIW, IW, RW(1:KERNEL_NPACK), ks, INFO)
    if (INFO /= FSYM_SUCCESS) return
    call fsym_kernel_abort(ks, X, V, RW(LEGACY_KC + 2 * IW(4)))
    call legacy_store(ks, RW(1:KERNEL_NPACK))
end subroutine FSYMRS

!> Check the calling convention: call it once with INTEGER ICHK(2) set to (1, 2). The
!> library expects default integers of 4 bytes and DOUBLE PRECISION of 8 bytes (the F77
!> convention of gfortran, ifx, nvfortran without -i8/-fdefault-integer-8). On return
!> ICHK(1) = ICHK(2) = 0 when the caller's integers are 4-byte ones, and FSYM_ERR_CONVENTION
!> (22) when they are 8-byte ones (a code built with -fdefault-integer-8 must not use the F77
!> face; the modern API and the C face have no such trap). X must be set to 1.5D0: a caller
!> whose DOUBLE PRECISION is not 8 bytes gets 22 as well.
subroutine FSYMCV(ICHK, X)
    use, intrinsic :: iso_fortran_env, only: int32
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_CONVENTION
    use fsym_kinds, only: wp, fsym_same
    implicit none
    integer(int32), intent(inout) :: ICHK(*)   !! (1, 2) on entry; the verdict on return
    real(wp), intent(in) :: X                  !! 1.5D0
    if (ICHK(1) == 1 .and. ICHK(2) == 2 .and. fsym_same(X, 1.5_wp)) then
        ICHK(1:2) = FSYM_SUCCESS
    else if (ICHK(1) == 1 .and. ICHK(2) == 0) then
        ! a little-endian 8-byte integer array (1, 2) seen as 4-byte words: 1, 0, 2, 0
        ICHK(1:4) = [FSYM_ERR_CONVENTION, 0, FSYM_ERR_CONVENTION, 0]
    else
        ICHK(1:2) = FSYM_ERR_CONVENTION
    end if
end subroutine FSYMCV

!> Length LCK of the checkpoint array of the work arrays set up by FSYMIN/FSYMIL for X(ND,N)
!> (INFO as FSYMST; FSYM_ERR_WORK_SIZE when the length does not fit a default integer).
subroutine FSYMCL(ND, N, RW, LRW, IW, LIW, LCK, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_WORK_SIZE
    use fsym_kinds, only: wp, ik
    use fsym_checkpoint, only: fsym_checkpoint_length
    use fsym_legacy_work, only: legacy_check
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(in) :: RW(LRW)             !! work array set up by FSYMIN
    integer, intent(in) :: IW(LIW)              !! work array set up by FSYMIN
    integer, intent(out) :: LCK                 !! checkpoint length
    integer, intent(out) :: INFO                !! status
    integer(ik) :: m
    LCK = 0
    INFO = legacy_check(ND, N, LRW, LIW, IW, RW)
    if (INFO /= FSYM_SUCCESS) return
    m = fsym_checkpoint_length(IW(4), ND, N, IW(5))
    if (m > huge(LCK)) then
        INFO = FSYM_ERR_WORK_SIZE; return
    end if
    LCK = int(m)
end subroutine FSYMCL

!> Checkpoint: the complete state (X, V, the method, the cached forces, the evaluation counts)
!> into CK(LCK), in the format of every face (`fsym_checkpoint`): a run restored from it by
!> FSYMCR (or by the modern or C face) goes on bitwise as if never interrupted. Not while a
!> reverse-communication step is in progress (INFO = 17). The F77 face keeps no clock: the
!> time and step count in CK are 0.
subroutine FSYMCK(ND, N, X, V, RW, LRW, IW, LIW, CK, LCK, INFO)
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_REQUEST, FSYM_ERR_CHECKPOINT
    use fsym_kinds, only: wp
    use fsym_kernel, only: kernel_state_t, fsym_kernel_request, KERNEL_NPACK, REQ_NONE
    use fsym_checkpoint, only: ckpt_clock_t, fsym_checkpoint_length, fsym_checkpoint_pack
    use fsym_legacy_work, only: legacy_check, legacy_load, LEGACY_KO, LEGACY_KC
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(in) :: X(ND, N)            !! positions
    real(wp), intent(in) :: V(ND, N)            !! velocities
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(in) :: RW(LRW)             !! work array set up by FSYMIN
    integer, intent(in) :: IW(LIW)              !! work array set up by FSYMIN
    integer, intent(in) :: LCK                  !! length of CK
    real(wp), intent(out) :: CK(LCK)            !! the checkpoint
    integer, intent(out) :: INFO                !! status
    type(kernel_state_t) :: ks
    type(ckpt_clock_t) :: clock
    integer :: nop, kw, req, at, into, given
    INFO = legacy_check(ND, N, LRW, LIW, IW, RW)
    if (INFO /= FSYM_SUCCESS) return
    nop = IW(4); kw = LEGACY_KC + 2 * nop
    if (LCK < fsym_checkpoint_length(nop, ND, N, IW(5))) then
        INFO = FSYM_ERR_CHECKPOINT; return
    end if
    call legacy_load(LIW, IW, RW(1:KERNEL_NPACK), ks, INFO)
    if (INFO /= FSYM_SUCCESS) return
    call fsym_kernel_request(ks, req, at, into, given)
    if (req /= REQ_NONE) then
        INFO = FSYM_ERR_BAD_REQUEST; return
    end if
    call fsym_checkpoint_pack(IW(LEGACY_KO:LEGACY_KO + nop - 1), RW(LEGACY_KC:kw - nop - 1), &
                              RW(kw - nop:kw - 1), ks, clock, X, V, &
                              RW(kw:kw - 1 + ND * N * IW(5)), CK)
end subroutine FSYMCK

!> Restart: restore X, V and the work arrays from a checkpoint CK written by FSYMCK (or by
!> the modern or C face, uncompensated) for the same method on X(ND,N); RW and IW must have
!> been set up by FSYMIN/FSYMIL for that method. INFO = 21 (FSYM_ERR_CHECKPOINT) when CK is
!> corrupt, of another version, method, shape or a compensated run; nothing changes then.
subroutine FSYMCR(ND, N, X, V, RW, LRW, IW, LIW, CK, LCK, INFO)
    use fsym_status, only: FSYM_SUCCESS
    use fsym_kinds, only: wp
    use fsym_kernel, only: kernel_state_t, KERNEL_NPACK
    use fsym_checkpoint, only: ckpt_clock_t, fsym_checkpoint_unpack
    use fsym_legacy_work, only: legacy_check, legacy_load, legacy_store, legacy_seal, &
                                LEGACY_KO, LEGACY_KC
    implicit none
    integer, intent(in) :: ND, N                !! dimensions, bodies
    real(wp), intent(inout) :: X(ND, N)         !! positions
    real(wp), intent(inout) :: V(ND, N)         !! velocities
    integer, intent(in) :: LRW, LIW             !! lengths of RW and IW
    real(wp), intent(inout) :: RW(LRW)          !! work array set up by FSYMIN
    integer, intent(inout) :: IW(LIW)           !! work array set up by FSYMIN
    integer, intent(in) :: LCK                  !! length of CK
    real(wp), intent(in) :: CK(LCK)             !! the checkpoint
    integer, intent(out) :: INFO                !! status
    type(kernel_state_t) :: ks
    type(ckpt_clock_t) :: clock
    integer :: nop, kw
    character(len=128) :: msg
    INFO = legacy_check(ND, N, LRW, LIW, IW, RW)
    if (INFO /= FSYM_SUCCESS) return
    nop = IW(4); kw = LEGACY_KC + 2 * nop
    call legacy_load(LIW, IW, RW(1:KERNEL_NPACK), ks, INFO)
    if (INFO /= FSYM_SUCCESS) return
    call fsym_checkpoint_unpack(CK, IW(LEGACY_KO:LEGACY_KO + nop - 1), &
                                RW(LEGACY_KC:kw - nop - 1), RW(kw - nop:kw - 1), ks, clock, &
                                X, V, RW(kw:kw - 1 + ND * N * IW(5)), INFO, msg)
    if (INFO /= FSYM_SUCCESS) return
    call legacy_store(ks, RW(1:KERNEL_NPACK))
    IW(7) = 0
    call legacy_seal(LIW, IW, LRW, RW)
end subroutine FSYMCR

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
