!> The one splitting kernel: it alone knows the stage semantics (the op codes below) and alone
!> reads or writes its state (`kernel_state_t`, private components). Every face runs it.
!> A step of size h runs the stages of a table (op, c, u) in order on (q, v):
!>
!> * `OP_DRIFT`        the model's flow of the other part of H over c h: free flight
!>                     q <- q + c h v unless the model overrides `drift` (a Kepler flow)
!> * `OP_KICK`         v <- v + c h a(q)
!> * `OP_GRAD_KICK`    v <- v + (c h a(q) + u h^3 g(q))   (g: the gradient term)
!> * `OP_EXTRAP_KICK`  v <- v + c h a(q + u h^2 a(q))     (the gradient by extrapolation)
!>
!> Rules, all here: the force at a step's end is reused while q is bitwise its point; a drift
!> forgets every cached force; the extrapolated force is reused at the same shift only. A step
!> never allocates and does no I/O; it completes or leaves q, v bitwise as on entry (the first
!> update of q and of v saves the old values in its loop, every update tests its new values
!> in that loop, a model's `stat` or a non-finite force undoes the step); a non-finite entry
!> state is refused. `ask` (reverse communication): every evaluation suspends the call
!> (`KERNEL_SUSPEND`); the caller fills the slot `fsym_kernel_request` names, then calls again.
module fsym_kernel
    use fsym_kinds, only: wp, ik, iwp, same => fsym_same
    use fsym_status
    use fsym_force, only: force_model_t, recorder_t, EVAL_FORCE, EVAL_GRADIENT, &
                          EVAL_EXTRAPOLATED
    use fsym_kernel_loops, only: fsym_all_finite, copy => fsym_loop_copy, &
        shifted => fsym_loop_shifted, update_comp => fsym_loop_update_comp, &
        update2_comp => fsym_loop_update2_comp, fsym_loop_entry
    implicit none
    private

    public :: fsym_kernel_layout, fsym_kernel_run, fsym_kernel_abort
    public :: fsym_kernel_invalidate, fsym_kernel_slots, fsym_kernel_counts
    public :: fsym_kernel_stage, fsym_kernel_request
    public :: fsym_kernel_pack, fsym_kernel_unpack, fsym_kernel_point_slots, fsym_all_finite

    integer, parameter, public :: OP_DRIFT = 1        !! flow of the other part: q <- q + c h v
    integer, parameter, public :: OP_KICK = 2         !! v <- v + c h a(q)
    integer, parameter, public :: OP_GRAD_KICK = 3    !! v <- v + c h a(q) + u h^3 g(q)
    integer, parameter, public :: OP_EXTRAP_KICK = 4  !! v <- v + c h a(q + u h^2 a(q))
    integer, parameter, public :: KERNEL_SUSPEND = -1    !! stat of a suspended call
    integer, parameter, public :: REQ_NONE = 0           !! no force outstanding
    integer, parameter, public :: REQ_FORCE = 1          !! a(q)
    integer, parameter, public :: REQ_GRADIENT = 2       !! g(q), given a(q)
    integer, parameter, public :: REQ_FORCE_SHIFTED = 3  !! a(x) at the shifted point x
    integer, parameter, public :: KERNEL_NPACK = 18      !! reals of a packed state
    real(wp), parameter, public :: KERNEL_PACK_TAG = 20261129.0_wp  !! last value of a packed state

    !> The kernel's state: where each array lives in the work array w(d, n, nslot), what the
    !> force cache holds, the step in progress and the counters. Only this module reads it.
    type, public :: kernel_state_t
        private
        integer :: d = 0, n = 0, nslot = 0, nop = 0
        integer :: ia = 1, ig = 1         ! slots: acceleration, gradient term at q
        integer :: iqe = 1, iae = 1       ! slots: shifted point, acceleration there
        integer :: iq0 = 1, iv0 = 1       ! slots: q, v at the start of the step
        integer :: iqlast = 1             ! slot: the point of the cached force
        integer :: iqc = 1, ivc = 1       ! slots: compensation terms of q, v
        integer :: iqc0 = 1, ivc0 = 1     ! slots: compensation terms at the step's start
        logical :: comp = .false.         ! Kahan-compensated updates
        logical :: have_a = .false., have_g = .false., have_x = .false.  ! cache valid
        logical :: active = .false.       ! a suspended step is in progress
        logical :: qsaved = .false., vsaved = .false.  ! q, v of the step's start saved
        integer :: pc = 0                 ! stage in progress or that failed (0: on entry)
        integer :: req = REQ_NONE         ! force outstanding while suspended
        real(wp) :: h = 0.0_wp            ! step of the step in progress
        real(wp) :: xshift = 0.0_wp       ! u h^2 of the cached extrapolated force
        integer(ik) :: nf = 0, ng = 0     ! force and gradient evaluations accepted
    end type kernel_state_t

contains

    !> Set up `ks` for a table on arrays (d, n): the slots it needs (methods without gradient
    !> or extrapolation, and runs without compensation, pay no memory for them). The caller
    !> then provides `w(d, n, fsym_kernel_slots(ks))`.
    pure subroutine fsym_kernel_layout(op, compensated, d, n, ks)
        integer, intent(in) :: op(:)                 !! the table's op codes
        logical, intent(in) :: compensated           !! Kahan-compensated updates
        integer, intent(in) :: d, n                  !! dimensions, particles
        type(kernel_state_t), intent(out) :: ks      !! the new state
        ks%d = d; ks%n = n; ks%nop = size(op); ks%comp = compensated
        ks%ia = 1; ks%iq0 = 2; ks%iv0 = 3; ks%iqlast = 4; ks%nslot = 4
        if (any(op == OP_GRAD_KICK)) then
            ks%ig = 5; ks%nslot = 5
        end if
        if (any(op == OP_EXTRAP_KICK)) then
            ks%iqe = ks%nslot + 1; ks%iae = ks%nslot + 2; ks%nslot = ks%nslot + 2
        end if
        if (compensated) then
            ks%iqc = ks%nslot + 1; ks%ivc = ks%nslot + 2; ks%iqc0 = ks%nslot + 3
            ks%ivc0 = ks%nslot + 4; ks%nslot = ks%nslot + 4
        end if
    end subroutine fsym_kernel_layout

    !> Take up to `nsteps` steps of size h (or resume a suspended step and go on); `ndone`
    !> are complete. On failure `stat` is an `FSYM_ERR_*` code, q and v the state after
    !> `ndone` steps, `fsym_kernel_stage` the failing stage. `stat = KERNEL_SUSPEND`: suspended
    !> (`ask` only). `step0`: steps before this call, for the recorder. `t0`: the time of this
    !> call's first step, for a model with `has_time()`: before each evaluation it is told the
    !> stage's time t0 + (steps done + drift weights so far) h.
    subroutine fsym_kernel_run(nop, op, c, u, model, ks, q, v, w, h, nsteps, ndone, stat, &
                               recorder, step0, ask, t0)
        integer, intent(in) :: nop                               !! number of stages
        integer, intent(in) :: op(nop)                           !! op codes of the stages
        real(wp), intent(in) :: c(nop), u(nop)                   !! stage coefficients
        class(force_model_t), intent(inout) :: model             !! force model
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout), target :: q(ks%d, ks%n), v(ks%d, ks%n)  !! state
        real(wp), intent(inout), target :: w(ks%d, ks%n, ks%nslot)       !! work array
        real(wp), intent(in) :: h                                !! step (for a new step)
        integer(ik), intent(in) :: nsteps                        !! steps to take
        integer(ik), intent(out) :: ndone                        !! steps completed
        integer, intent(out) :: stat                             !! status
        class(recorder_t), intent(inout), optional :: recorder   !! force-point recorder
        integer(ik), intent(in), optional :: step0               !! steps before this call
        logical, intent(in), optional :: ask
            !! reverse communication: suspend at every evaluation instead of calling the model
        real(wp), intent(in), optional :: t0                     !! time of the first step
        real(wp), pointer, contiguous :: a(:, :), g(:, :), x(:, :)
        integer(ik) :: i, s0
        integer :: k, m, iy, iyf, mst
        real(wp) :: hs, shift, tau
        logical :: qok, vok, vwas, fresh, fa, resumed, two, rec, rc, flow, moved, timed

        ndone = 0; stat = FSYM_SUCCESS; m = ks%d * ks%n; s0 = 0; rc = .false.
        if (present(step0)) s0 = step0
        if (present(ask)) rc = ask
        rec = present(recorder)
        a => w(:, :, ks%ia); g => w(:, :, ks%ig)
        if (.not. ks%active) then
            if (nsteps < 1) return
            ks%pc = 0
            if (same(h, 0.0_wp) .or. .not. abs(h) <= huge(h)) then
                stat = FSYM_ERR_BAD_STEP; return
            end if
            if (.not. fsym_loop_entry(m, q, v, w(:, :, ks%iqlast), ks%have_a, moved)) then
                stat = FSYM_ERR_NONFINITE_STATE; return      ! refused, the cache kept
            end if
            if (moved) call fsym_kernel_invalidate(ks)
        end if
        flow = model%has_drift(); timed = .false.; tau = 0.0_wp; hs = h
        if (present(t0)) timed = model%has_time()
        steps: do i = 1, max(nsteps, 1_ik)
            qok = .true.; vok = .true.; resumed = ks%active
            if (resumed) then
                ! resume: the caller has put the requested force into its slot
                hs = ks%h
                if (.not. accepted(ks%req, .true.)) return
                ks%active = .false.; ks%req = REQ_NONE
            else
                ks%qsaved = ks%comp; ks%vsaved = ks%comp      ! compensated: all saved here
                if (ks%comp) then
                    w(:, :, ks%iq0) = q; w(:, :, ks%iv0) = v
                    w(:, :, ks%iqc0) = w(:, :, ks%iqc); w(:, :, ks%ivc0) = w(:, :, ks%ivc)
                end if
                ks%h = hs; ks%pc = 1
            end if
            if (timed) tau = real(ndone, wp) + sum(c(1:ks%pc - 1), mask=op(1:ks%pc - 1) == OP_DRIFT)
            do k = ks%pc, nop
                ks%pc = k
                if (timed .and. op(k) /= OP_DRIFT) call model%set_time(t0 + tau * hs)
                if (op(k) == OP_DRIFT) then
                    if (timed) tau = tau + c(k)
                    if (flow) then
                        if (.not. drifted(c(k) * hs)) return
                    else
                        qok = upd(q, w(:, :, ks%iqc), w(:, :, ks%iq0), c(k) * hs, v, 0.0_wp, &
                                  v, .false., ks%qsaved) .and. qok
                        ks%qsaved = .true.
                    end if
                    call fsym_kernel_invalidate(ks)
                    cycle
                end if
                ! a kick: the forces it needs (slot iy; iyf: the one evaluated for it), the
                ! update; recording, suspension and failures in `noted`
                fa = .not. ks%have_a; iy = ks%ia; iyf = ks%ia
                if (fa) then
                    if (rc) then
                        call suspend(REQ_FORCE); return
                    end if
                    mst = 0; call model%acceleration(q, a, mst)
                    if (mst /= 0 .or. rec .or. op(k) == OP_EXTRAP_KICK) then
                        if (.not. noted(REQ_FORCE, mst, op(k) == OP_EXTRAP_KICK)) return
                    else
                        ks%have_a = .true.; ks%nf = ks%nf + 1
                    end if
                end if
                select case (op(k))
                case (OP_GRAD_KICK)
                    fresh = .not. ks%have_g; iyf = ks%ig
                    if (fresh) then
                        if (rc) then
                            call suspend(REQ_GRADIENT); return
                        end if
                        mst = 0; call model%gradient(q, a, g, mst)
                        if (mst /= 0 .or. rec) then
                            if (.not. noted(REQ_GRADIENT, mst, .false.)) return
                        else
                            ks%have_g = .true.; ks%ng = ks%ng + 1
                        end if
                    end if
                case (OP_EXTRAP_KICK)
                    shift = u(k) * hs * hs; iy = ks%iae; iyf = ks%iae; fa = .false.
                    fresh = .not. (ks%have_x .and. ks%xshift <= shift .and. ks%xshift >= shift)
                    if (fresh) then
                        call shifted(m, q, shift, a, w(:, :, ks%iqe))
                        ks%xshift = shift; ks%have_x = .false.
                        if (rc) then
                            call suspend(REQ_FORCE_SHIFTED); return
                        end if
                        mst = 0; call model%acceleration(w(:, :, ks%iqe), w(:, :, ks%iae), mst)
                        if (.not. noted(REQ_FORCE_SHIFTED, mst, .false.)) return
                    end if
                case default
                    fresh = fa; fa = .false.
                end select
                vwas = vok; two = op(k) == OP_GRAD_KICK
                vok = upd(v, w(:, :, ks%ivc), w(:, :, ks%iv0), c(k) * hs, w(:, :, iy), &
                          u(k) * hs**3, g, two, ks%vsaved)
                ks%vsaved = .true.
                if (.not. (vok .or. forces_ok(w(:, :, iyf), two, fa, vwas))) return
            end do
            ks%pc = nop + 1
            if (resumed) then     ! the tests of the stages before the suspension are gone
                qok = fsym_all_finite(m, q); vok = fsym_all_finite(m, v)
            end if
            if (.not. (qok .and. vok)) then
                call fail(FSYM_ERR_NONFINITE_STATE); return
            end if
            ndone = ndone + 1
            if (ndone >= nsteps) exit steps
        end do steps
        if (ks%have_a) call copy(m, q, w(:, :, ks%iqlast))

    contains

        !> x <- x + s y, or x + (s y + r y2) when `two` (compensated in e when `ks%comp`), the
        !> old x into x0 unless `saved`; true when the new x is all finite.
        logical function upd(x, e, x0, s, y, r, y2, two, saved) result(ok)
            real(wp), intent(inout) :: x(m), e(m), x0(m)
            real(wp), intent(in) :: s, y(m), r, y2(m)
            logical, intent(in) :: two, saved
            real(wp) :: t
            integer :: j
            integer(iwp) :: bad
            if (ks%comp) then
                if (two) ok = update2_comp(m, x, e, s, y, r, y2)
                if (.not. two) ok = update_comp(m, x, e, s, y)
                return
            end if
            bad = 0
            do j = 1, m
                t = x(j)
                if (two) x(j) = t + (s * y(j) + r * y2(j))
                if (.not. two) x(j) = t + s * y(j)
                bad = ior(bad, transfer(x(j) - x(j), bad))    ! see fsym_kernel_loops
                if (.not. saved) x0(j) = t
            end do
            ok = iand(bad, huge(bad)) == 0
        end function upd

        !> A drift by the model's own flow over dt: q and v saved first (the flow moves both);
        !> false, the step undone, when the model fails or leaves a value that is not finite.
        logical function drifted(dt)
            real(wp), intent(in) :: dt
            if (.not. ks%qsaved) call copy(m, q, w(:, :, ks%iq0))
            if (.not. ks%vsaved) call copy(m, v, w(:, :, ks%iv0))
            ks%qsaved = .true.; ks%vsaved = .true.
            mst = 0
            call model%drift(q, v, dt, mst)
            drifted = mst == 0
            if (.not. drifted) then
                call fail(FSYM_ERR_MODEL); return
            end if
            drifted = fsym_all_finite(m, q) .and. fsym_all_finite(m, v)
            if (.not. drifted) call fail(FSYM_ERR_NONFINITE_STATE)
        end function drifted

        !> After a kick whose new v is not all finite: false (step undone, forces uncounted)
        !> when a force evaluated for it is not: a(q) for a gradient kick (`fa`), then y
        !> (`fresh`; `grad`: the gradient term). The model's fault only where the state it was
        !> evaluated at (q, and v before the kick, `vwas`) is finite.
        logical function forces_ok(y, grad, fa, vwas)
            real(wp), intent(in) :: y(m)
            logical, intent(in) :: grad, fa, vwas
            logical :: fy
            fy = .true.
            if (fa) fy = fsym_all_finite(m, a)
            forces_ok = fy
            if (forces_ok .and. fresh) forces_ok = fsym_all_finite(m, y)
            if (forces_ok) return
            if (grad .and. fresh) ks%ng = ks%ng - 1
            if (.not. (fy .and. grad)) ks%nf = ks%nf - 1
            call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                            fsym_all_finite(m, q) .and. (vwas .or. fy)))
        end function forces_ok

        !> After an evaluation with a recorder, a non-zero model `stat` or a force to `check`:
        !> record the point, accept the force (`accepted`); false when the model failed or the
        !> force is not finite (the step undone).
        logical function noted(req, mst, check)
            integer, intent(in) :: req, mst
            logical, intent(in) :: check
            if (present(recorder)) then
                x => q
                if (req == REQ_FORCE_SHIFTED) x => w(:, :, ks%iqe)
                call recorder%record(s0 + ndone + 1, ks%pc, merge(EVAL_GRADIENT, merge( &
                    EVAL_EXTRAPOLATED, EVAL_FORCE, req == REQ_FORCE_SHIFTED), &
                    req == REQ_GRADIENT), x)
            end if
            noted = mst == 0
            if (.not. noted) call fail(FSYM_ERR_MODEL)
            if (noted) noted = accepted(req, check)
        end function noted

        !> Mark a force put into its slot valid and count it; when `check`, first check it
        !> (false, step undone, if it is not finite: the model's fault where the state is).
        logical function accepted(req, check)
            integer, intent(in) :: req
            logical, intent(in) :: check
            integer :: slot
            slot = merge(ks%ig, merge(ks%iae, ks%ia, req == REQ_FORCE_SHIFTED), req == REQ_GRADIENT)
            accepted = .true.
            if (check) accepted = fsym_all_finite(m, w(:, :, slot))
            if (.not. accepted) then
                call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                                fsym_all_finite(m, q) .and. fsym_all_finite(m, v)))
            else if (req == REQ_GRADIENT) then
                ks%have_g = .true.; ks%ng = ks%ng + 1
            else
                ks%have_a = ks%have_a .or. req == REQ_FORCE; ks%nf = ks%nf + 1
                ks%have_x = ks%have_x .or. req == REQ_FORCE_SHIFTED
            end if
        end function accepted

        !> Suspend the step for the caller's force `req`.
        subroutine suspend(req)
            integer, intent(in) :: req
            ks%active = .true.; ks%req = req; stat = KERNEL_SUSPEND
        end subroutine suspend

        !> Undo the step in progress and report `code`.
        subroutine fail(code)
            integer, intent(in) :: code
            ks%active = .true.
            call fsym_kernel_abort(ks, q, v, w)
            stat = code
        end subroutine fail

    end subroutine fsym_kernel_run

    !> Undo a suspended step, or with `completed` the step just completed by a one-step call
    !> (a step-size guard that finds its end beyond the limit): q, v (and the compensation
    !> terms) as at its start, each saved by the step's first update of it; the cache is
    !> forgotten, the counters keep the evaluations made.
    subroutine fsym_kernel_abort(ks, q, v, w, completed)
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n)  !! state, restored
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)       !! work array
        logical, intent(in), optional :: completed               !! undo the completed step
        if (present(completed)) ks%active = ks%active .or. completed
        if (ks%active) then
            if (ks%qsaved) q = w(:, :, ks%iq0)
            if (ks%vsaved) v = w(:, :, ks%iv0)
            if (ks%comp) then
                w(:, :, ks%iqc) = w(:, :, ks%iqc0); w(:, :, ks%ivc) = w(:, :, ks%ivc0)
            end if
        end if
        call fsym_kernel_invalidate(ks)
        ks%active = .false.; ks%req = REQ_NONE
    end subroutine fsym_kernel_abort

    !> Forget every cached force (after changing the model's parameters between steps).
    pure subroutine fsym_kernel_invalidate(ks)
        type(kernel_state_t), intent(inout) :: ks  !! kernel state
        ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
    end subroutine fsym_kernel_invalidate

    !> Slots of d*n reals the work array needs.
    pure integer function fsym_kernel_slots(ks)
        type(kernel_state_t), intent(in) :: ks  !! kernel state
        fsym_kernel_slots = ks%nslot
    end function fsym_kernel_slots

    !> Force and gradient evaluations accepted since the state was laid out.
    pure subroutine fsym_kernel_counts(ks, nf, ng)
        type(kernel_state_t), intent(in) :: ks   !! kernel state
        integer(ik), intent(out) :: nf, ng       !! force, gradient evaluations
        nf = ks%nf; ng = ks%ng
    end subroutine fsym_kernel_counts

    !> The stage in progress, or that failed in the last call (0: refused on entry; the
    !> number of stages + 1: the step's new state was not finite).
    pure integer function fsym_kernel_stage(ks)
        type(kernel_state_t), intent(in) :: ks  !! kernel state
        fsym_kernel_stage = ks%pc
    end function fsym_kernel_stage

    !> The force a suspended step waits for (`REQ_*`; REQ_NONE: none suspended), its slots in the
    !> work array: the point it is wanted at (0: q itself), the slot it goes into, and the
    !> slot holding a(q) that a gradient request is given (else 0).
    pure subroutine fsym_kernel_request(ks, req, at, into, given)
        type(kernel_state_t), intent(in) :: ks   !! kernel state
        integer, intent(out) :: req              !! the request
        integer, intent(out) :: at, into, given  !! slots
        req = REQ_NONE; at = 0; into = 0; given = 0
        if (.not. ks%active) return
        req = ks%req
        select case (req)
        case (REQ_FORCE)
            into = ks%ia
        case (REQ_GRADIENT)
            into = ks%ig; given = ks%ia
        case (REQ_FORCE_SHIFTED)
            at = ks%iqe; into = ks%iae
        case default
            req = REQ_NONE
        end select
    end subroutine fsym_kernel_request

    !> The slots of q at a step's start and of the cached force's point (version-1 checkpoints).
    pure subroutine fsym_kernel_point_slots(ks, start, cached)
        type(kernel_state_t), intent(in) :: ks   !! kernel state
        integer, intent(out) :: start, cached    !! slots
        start = ks%iq0; cached = ks%iqlast
    end subroutine fsym_kernel_point_slots

    !> The state as `KERNEL_NPACK` reals (integers exact as doubles): the one image of it that
    !> the F77 work array and the checkpoint keep. r(1:4) = h, shift, force and gradient counts.
    pure subroutine fsym_kernel_pack(ks, r)
        type(kernel_state_t), intent(in) :: ks        !! kernel state
        real(wp), intent(out) :: r(KERNEL_NPACK)      !! its image
        r = [ks%h, ks%xshift, real(ks%nf, wp), real(ks%ng, wp), real(ks%d, wp), &
             real(ks%n, wp), real(ks%nslot, wp), flag(ks%comp), flag(ks%have_a), &
             flag(ks%have_g), flag(ks%have_x), flag(ks%active), flag(ks%qsaved), &
             flag(ks%vsaved), real(ks%pc, wp), real(ks%req, wp), real(ks%nop, wp), KERNEL_PACK_TAG]
    end subroutine fsym_kernel_pack

    !> Take over an image written by `fsym_kernel_pack` into `ks`, which the caller has laid out
    !> (`fsym_kernel_layout`) for the same table and arrays: the image must agree with that
    !> layout, and every flag and count must be in range. Otherwise `stat` =
    !> FSYM_ERR_CHECKPOINT, `msg` names the field, and `ks` is unchanged.
    pure subroutine fsym_kernel_unpack(r, ks, stat, msg)
        real(wp), intent(in) :: r(KERNEL_NPACK)     !! the image
        type(kernel_state_t), intent(inout) :: ks   !! laid out; the state on success
        integer, intent(out) :: stat                !! status
        character(len=*), intent(inout) :: msg      !! which field does not fit
        stat = FSYM_ERR_CHECKPOINT
        if (.not. same(r(KERNEL_NPACK), KERNEL_PACK_TAG)) then
            msg = 'kernel state: not a packed kernel state (tag)'
        else if (.not. all(same(r([5, 6, 7, 17]), real([ks%d, ks%n, ks%nslot, ks%nop], wp)))) then
            msg = 'kernel state: dimensions, particles, slots or stages differ from this one'
        else if (.not. same(r(8), flag(ks%comp))) then
            msg = 'kernel state: compensated in one, not in the other'
        else if (.not. all(same(r(8:14), 0.0_wp) .or. same(r(8:14), 1.0_wp))) then
            msg = 'kernel state: a flag is neither 0 nor 1'
        else if (.not. all(r(3:4) >= 0.0_wp .and. r(3:4) < 2.0_wp**53)) then
            msg = 'kernel state: evaluation counts out of range'
        else if (.not. (r(15) >= 0.0_wp .and. r(15) <= ks%nop + 1 .and. &
                        same(r(15), aint(r(15))) .and. r(16) >= REQ_NONE .and. &
                        r(16) <= REQ_FORCE_SHIFTED .and. same(r(16), aint(r(16))))) then
            msg = 'kernel state: stage or request out of range'
        else if (.not. (abs(r(1)) <= huge(r(1)) .and. abs(r(2)) <= huge(r(2)))) then
            msg = 'kernel state: step or shift not finite'
        else
            ks%h = r(1); ks%xshift = r(2); ks%nf = int(r(3), ik); ks%ng = int(r(4), ik)
            ks%have_a = same(r(9), 1.0_wp); ks%have_g = same(r(10), 1.0_wp)
            ks%have_x = same(r(11), 1.0_wp); ks%active = same(r(12), 1.0_wp)
            ks%qsaved = same(r(13), 1.0_wp); ks%vsaved = same(r(14), 1.0_wp)
            ks%pc = nint(r(15)); ks%req = nint(r(16))
            stat = FSYM_SUCCESS
        end if
    end subroutine fsym_kernel_unpack

    pure real(wp) function flag(x)
        logical, intent(in) :: x
        flag = merge(1.0_wp, 0.0_wp, x)
    end function flag

end module fsym_kernel
