!> The one splitting kernel: a loop over steps with the loop over the stage table inside,
!> calling the force model directly; it knows no model. The modern integrator, the F77 face
!> (EXTERNAL routines in a small model type), reverse communication and the C face run it.
!> State: `kernel_state_t` (`fsym_kernel_state`) with a caller-owned work array
!> `w(d, n, nslot)`. A step never allocates and does no I/O; it completes or leaves q, v
!> (and the compensation terms) bitwise as on entry: every force and new state is checked
!> for NaN/Inf, a model's non-zero `stat` undoes it. The end-of-step force is reused when q
!> is bitwise unchanged (first-same-as-last). Resumable form: a model's evaluation setting
!> `stat = KERNEL_SUSPEND` suspends the step; `ks%req` names the force the caller puts into
!> its slot, and the next `fsym_kernel_run` resumes at that stage.
module fsym_kernel
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_scheme, only: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use fsym_force, only: force_model_t, recorder_t, EVAL_FORCE, EVAL_GRADIENT, &
                          EVAL_EXTRAPOLATED
    use fsym_kernel_state, only: kernel_state_t, KERNEL_SUSPEND, REQ_NONE, REQ_FORCE, &
                                 REQ_GRADIENT, REQ_FORCE_SHIFTED
    implicit none
    private

    public :: kernel_state_t, KERNEL_SUSPEND, REQ_NONE, REQ_FORCE, REQ_GRADIENT
    public :: REQ_FORCE_SHIFTED
    public :: fsym_kernel_layout, fsym_kernel_run, fsym_kernel_abort, fsym_kernel_invalidate
    public :: fsym_all_finite

contains

    !> Set up `ks` for a scheme on arrays (d, n): the slots it needs (methods without
    !> gradient or extrapolation, and runs without compensation, pay no memory for them).
    !> The caller then provides `w(d, n, ks%nslot)`.
    pure subroutine fsym_kernel_layout(op, compensated, d, n, ks)
        integer, intent(in) :: op(:)                 !! the scheme's op codes
        logical, intent(in) :: compensated           !! Kahan-compensated updates
        integer, intent(in) :: d, n                  !! dimensions, particles
        type(kernel_state_t), intent(out) :: ks      !! the new state
        ks%d = d; ks%n = n; ks%comp = compensated
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

    !> True when all m values are finite: one sum in 16 interleaved partial sums (it
    !> vectorises), an element-wise look only when the sum is not finite.
    pure logical function fsym_all_finite(m, x)
        integer, intent(in) :: m         !! number of values
        real(wp), intent(in) :: x(m)     !! values
        real(wp) :: acc(16), s
        integer :: i, mb
        mb = m - mod(m, 16); s = 0.0_wp
        if (mb > 0) then
            acc = x(1:16)
            do i = 17, mb, 16
                acc = acc + x(i:i + 15)
            end do
            s = sum(acc)
        end if
        do i = mb + 1, m
            s = s + x(i)
        end do
        fsym_all_finite = abs(s) <= huge(s)
        if (.not. fsym_all_finite) fsym_all_finite = all(ieee_is_finite(x))
    end function fsym_all_finite

    !> Forget every cached force (after changing the model's parameters between steps).
    pure subroutine fsym_kernel_invalidate(ks)
        type(kernel_state_t), intent(inout) :: ks  !! kernel state
        ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
    end subroutine fsym_kernel_invalidate

    !> Undo a suspended step: restore q, v (and the compensation terms) saved at its start.
    subroutine fsym_kernel_abort(ks, q, v, w)
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n)  !! state, restored
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)       !! work array
        if (ks%active) then
            q = w(:, :, ks%iq0); v = w(:, :, ks%iv0)
            if (ks%comp) then
                w(:, :, ks%iqc) = w(:, :, ks%iqc0); w(:, :, ks%ivc) = w(:, :, ks%ivc0)
            end if
        end if
        call fsym_kernel_invalidate(ks)
        ks%active = .false.; ks%req = REQ_NONE
    end subroutine fsym_kernel_abort

    !> Take up to `nsteps` steps of size h (or resume a suspended step and go on). On return
    !> `ndone` steps are complete. On failure `stat` is an `FSYM_ERR_*` code, q and v are the
    !> state after `ndone` steps, and `ks%pc` names the failing stage (0: refused on entry,
    !> nop + 1: the new state). `stat = KERNEL_SUSPEND`: the model suspended the step
    !> (`ks%req`). `step0` numbers the steps for the recorder (step0 + 1 is the first).
    subroutine fsym_kernel_run(op, c, u, model, ks, q, v, w, h, nsteps, ndone, stat, &
                               recorder, step0)
        integer, intent(in), contiguous :: op(:)                 !! op codes of the stages
        real(wp), intent(in), contiguous :: c(:), u(:)           !! stage coefficients
        class(force_model_t), intent(inout) :: model             !! force model
        type(kernel_state_t), intent(inout) :: ks                !! kernel state
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n)  !! state
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)       !! work array
        real(wp), intent(in) :: h                                !! step (for a new step)
        integer(ik), intent(in) :: nsteps                        !! steps to take
        integer(ik), intent(out) :: ndone                        !! steps completed
        integer, intent(out) :: stat                             !! status
        class(recorder_t), intent(inout), optional :: recorder   !! force-point recorder
        integer(ik), intent(in), optional :: step0               !! steps before this call
        integer(ik) :: i
        integer :: k, m
        real(wp) :: hs, shift

        ndone = 0; stat = FSYM_SUCCESS; m = ks%d * ks%n
        if (.not. ks%active) then
            if (nsteps < 1) return
            ks%pc = 0
            if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
                stat = FSYM_ERR_BAD_STEP; return
            end if
            if (.not. (fsym_all_finite(m, q) .and. fsym_all_finite(m, v))) then
                stat = FSYM_ERR_NONFINITE_STATE; return
            end if
            if (ks%have_a) then
                if (any(q /= w(:, :, ks%iqlast))) call fsym_kernel_invalidate(ks)
            end if
        end if
        hs = h
        steps: do i = 1, max(nsteps, 1_ik)
            if (ks%active) then
                ! resume: the caller has put the requested force into its slot
                hs = ks%h
                if (.not. accepted(ks%req)) return
                ks%active = .false.; ks%req = REQ_NONE
            else
                call copy(q, w(:, :, ks%iq0)); call copy(v, w(:, :, ks%iv0))
                if (ks%comp) then
                    call copy(w(:, :, ks%iqc), w(:, :, ks%iqc0))
                    call copy(w(:, :, ks%ivc), w(:, :, ks%ivc0))
                end if
                ks%h = hs; ks%pc = 1
            end if
            do k = ks%pc, size(op)
                ks%pc = k
                select case (op(k))
                case (OP_DRIFT)
                    call update(q, w(:, :, ks%iqc), c(k) * hs, v)
                    ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
                case (OP_KICK)
                    if (.not. ready(REQ_FORCE)) return
                    call update(v, w(:, :, ks%ivc), c(k) * hs, w(:, :, ks%ia))
                case (OP_GRAD_KICK)
                    if (.not. ready(REQ_FORCE)) return
                    if (.not. ready(REQ_GRADIENT)) return
                    call update2(v, w(:, :, ks%ivc), c(k) * hs, w(:, :, ks%ia), u(k) * hs**3, &
                                 w(:, :, ks%ig))
                case (OP_EXTRAP_KICK)
                    if (.not. ready(REQ_FORCE)) return
                    shift = u(k) * hs * hs
                    if (.not. ks%have_x .or. ks%xshift /= shift) then
                        w(:, :, ks%iqe) = q + shift * w(:, :, ks%ia)
                        ks%xshift = shift; ks%have_x = .false.
                        if (.not. evaluated(REQ_FORCE_SHIFTED)) return
                    end if
                    call update(v, w(:, :, ks%ivc), c(k) * hs, w(:, :, ks%iae))
                case default
                    continue      ! a validated scheme has no other op codes
                end select
            end do
            ks%pc = size(op) + 1
            if (.not. (fsym_all_finite(m, q) .and. fsym_all_finite(m, v))) then
                call fail(FSYM_ERR_NONFINITE_STATE); return
            end if
            ndone = ndone + 1
            if (ndone >= nsteps) exit steps
        end do steps
        if (ks%have_a) w(:, :, ks%iqlast) = q

    contains

        !> a(q) (or g(q)) is cached or now evaluated; false when the step failed or suspended.
        logical function ready(req)
            integer, intent(in) :: req
            ready = ks%have_a
            if (req == REQ_GRADIENT) ready = ks%have_g
            if (.not. ready) ready = evaluated(req)
        end function ready

        !> Evaluate what `req` names, record it, accept it; false when the step failed
        !> (undone) or was suspended.
        logical function evaluated(req)
            integer, intent(in) :: req
            integer :: mst, kind
            mst = 0
            select case (req)
            case (REQ_FORCE)
                call model%acceleration(q, w(:, :, ks%ia), mst); kind = EVAL_FORCE
            case (REQ_GRADIENT)
                call model%gradient(q, w(:, :, ks%ia), w(:, :, ks%ig), mst); kind = EVAL_GRADIENT
            case default
                call model%acceleration(w(:, :, ks%iqe), w(:, :, ks%iae), mst)
                kind = EVAL_EXTRAPOLATED
            end select
            evaluated = .false.
            if (mst == KERNEL_SUSPEND) then
                ks%active = .true.; ks%req = req; stat = KERNEL_SUSPEND
                return
            end if
            if (present(recorder)) then
                if (kind /= EVAL_EXTRAPOLATED) call recorder%record(step_no(), ks%pc, kind, q)
                if (kind == EVAL_EXTRAPOLATED) call recorder%record(step_no(), ks%pc, kind, &
                                                                    w(:, :, ks%iqe))
            end if
            if (mst /= 0) then
                call fail(FSYM_ERR_MODEL); return
            end if
            evaluated = accepted(req)
        end function evaluated

        !> Check a force put into its slot and mark it valid; false (step undone) if it is
        !> not finite.
        logical function accepted(req)
            integer, intent(in) :: req
            integer :: slot
            slot = ks%ia
            if (req == REQ_GRADIENT) slot = ks%ig
            if (req == REQ_FORCE_SHIFTED) slot = ks%iae
            accepted = fsym_all_finite(m, w(:, :, slot))
            if (.not. accepted) then     ! the model's fault only where the state is finite
                call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                                fsym_all_finite(m, q) .and. fsym_all_finite(m, v)))
                return
            end if
            if (req == REQ_GRADIENT) then
                ks%have_g = .true.; ks%ng = ks%ng + 1
            else
                ks%have_a = ks%have_a .or. req == REQ_FORCE; ks%nf = ks%nf + 1
                ks%have_x = ks%have_x .or. req == REQ_FORCE_SHIFTED
            end if
        end function accepted

        integer(ik) function step_no()
            step_no = ndone + 1
            if (present(step0)) step_no = step0 + ndone + 1
        end function step_no

        !> Undo the step in progress and report `code`.
        subroutine fail(code)
            integer, intent(in) :: code
            ks%active = .true.
            call fsym_kernel_abort(ks, q, v, w)
            stat = code
        end subroutine fail

        pure subroutine copy(x, y)
            real(wp), intent(in) :: x(m)
            real(wp), intent(out) :: y(m)
            y = x
        end subroutine copy

        !> x <- x + s y, Kahan-compensated in e when `ks%comp`.
        subroutine update(x, e, s, y)
            real(wp), intent(inout) :: x(m), e(m)
            real(wp), intent(in) :: s, y(m)
            real(wp) :: inc, t
            integer :: j
            if (ks%comp) then
                do j = 1, m
                    inc = s * y(j) - e(j); t = x(j) + inc; e(j) = (t - x(j)) - inc; x(j) = t
                end do
            else
                do j = 1, m
                    x(j) = x(j) + s * y(j)
                end do
            end if
        end subroutine update

        !> x <- x + (s y + r z), Kahan-compensated in e when `ks%comp`.
        subroutine update2(x, e, s, y, r, z)
            real(wp), intent(inout) :: x(m), e(m)
            real(wp), intent(in) :: s, y(m), r, z(m)
            real(wp) :: inc, t
            integer :: j
            if (ks%comp) then
                do j = 1, m
                    inc = (s * y(j) + r * z(j)) - e(j); t = x(j) + inc; e(j) = (t - x(j)) - inc
                    x(j) = t
                end do
            else
                do j = 1, m
                    x(j) = x(j) + (s * y(j) + r * z(j))
                end do
            end if
        end subroutine update2

    end subroutine fsym_kernel_run

end module fsym_kernel
