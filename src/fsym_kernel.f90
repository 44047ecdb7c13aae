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
    use fsym_kernel_loops, only: fsym_all_finite, copy => fsym_loop_copy, &
        shifted => fsym_loop_shifted, update => fsym_loop_update, update2 => fsym_loop_update2, &
        same => fsym_loop_same, save => fsym_loop_save
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
    !> Checks: every update tests its new values in the same loop. A force evaluated for a
    !> kick is checked by that test: x + s y is NaN or Inf wherever y is (NaN * s is NaN for
    !> any s, Inf * s is Inf, or NaN when s = 0), so a failed test looks at y itself to tell a
    !> non-finite force (the stage fails) from a non-finite state (the step fails at its end,
    !> as the last drift's and the last kick's tests say). Other forces are checked at once.
    subroutine fsym_kernel_run(op, c, u, model, ks, q, v, w, h, nsteps, ndone, stat, &
                               recorder, step0)
        integer, intent(in), contiguous :: op(:)                 !! op codes of the stages
        real(wp), intent(in), contiguous :: c(:), u(:)           !! stage coefficients
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
        real(wp), pointer, contiguous :: qp(:, :), a(:, :), g(:, :), qe(:, :), ae(:, :)
        integer(ik) :: i
        integer :: k, m
        real(wp) :: hs, shift
        logical :: qok, vok, fresh, resumed, saved

        ndone = 0; stat = FSYM_SUCCESS; m = ks%d * ks%n; saved = .false.
        qp => q; a => w(:, :, ks%ia); g => w(:, :, ks%ig)      ! descriptors made once
        qe => w(:, :, ks%iqe); ae => w(:, :, ks%iae)
        if (.not. ks%active) then
            if (nsteps < 1) return
            ks%pc = 0
            if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
                stat = FSYM_ERR_BAD_STEP; return
            end if
            ! the check of the state on entry saves it for the first step in the same loops
            saved = save(m, q, w(:, :, ks%iq0))
            if (saved) saved = save(m, v, w(:, :, ks%iv0))
            if (.not. saved) then
                stat = FSYM_ERR_NONFINITE_STATE; return
            end if
            if (ks%have_a) then
                if (.not. same(m, q, w(:, :, ks%iqlast))) call fsym_kernel_invalidate(ks)
            end if
        end if
        hs = h
        steps: do i = 1, max(nsteps, 1_ik)
            qok = .true.; vok = .true.; resumed = ks%active
            if (resumed) then
                ! resume: the caller has put the requested force into its slot
                hs = ks%h
                if (.not. accepted(ks%req, .true.)) return
                ks%active = .false.; ks%req = REQ_NONE
            else
                if (.not. saved) then
                    call copy(m, q, w(:, :, ks%iq0)); call copy(m, v, w(:, :, ks%iv0))
                end if
                saved = .false.
                if (ks%comp) then
                    call copy(m, w(:, :, ks%iqc), w(:, :, ks%iqc0))
                    call copy(m, w(:, :, ks%ivc), w(:, :, ks%ivc0))
                end if
                ks%h = hs; ks%pc = 1
            end if
            do k = ks%pc, size(op)
                ks%pc = k
                select case (op(k))
                case (OP_DRIFT)
                    qok = update(ks%comp, m, q, w(:, :, ks%iqc), c(k) * hs, v)
                    ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
                case (OP_KICK)
                    fresh = .not. ks%have_a
                    if (fresh) then
                        if (.not. evaluated(REQ_FORCE, .false.)) return
                    end if
                    vok = update(ks%comp, m, v, w(:, :, ks%ivc), c(k) * hs, a)
                    if (.not. force_ok(a, .false.)) return
                case (OP_GRAD_KICK)
                    if (.not. ready(REQ_FORCE)) return
                    fresh = .not. ks%have_g
                    if (fresh) then
                        if (.not. evaluated(REQ_GRADIENT, .false.)) return
                    end if
                    vok = update2(ks%comp, m, v, w(:, :, ks%ivc), c(k) * hs, a, u(k) * hs**3, g)
                    if (.not. force_ok(g, .true.)) return
                case (OP_EXTRAP_KICK)
                    if (.not. ready(REQ_FORCE)) return
                    shift = u(k) * hs * hs
                    fresh = .not. ks%have_x .or. ks%xshift /= shift
                    if (fresh) then
                        call shifted(m, q, shift, a, qe)
                        ks%xshift = shift; ks%have_x = .false.
                        if (.not. evaluated(REQ_FORCE_SHIFTED, .false.)) return
                    end if
                    vok = update(ks%comp, m, v, w(:, :, ks%ivc), c(k) * hs, ae)
                    if (.not. force_ok(ae, .false.)) return
                case default
                    continue      ! a validated scheme has no other op codes
                end select
            end do
            ks%pc = size(op) + 1
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

        !> a(q) (or g(q)) is cached or now evaluated and checked; false when the step failed
        !> or suspended.
        logical function ready(req)
            integer, intent(in) :: req
            ready = ks%have_a
            if (req == REQ_GRADIENT) ready = ks%have_g
            if (.not. ready) ready = evaluated(req, .true.)
        end function ready

        !> After a kick whose new v is not all finite: false (force uncounted, step undone)
        !> when the force y evaluated for it (`fresh`) is not finite.
        logical function force_ok(y, grad)
            real(wp), intent(in) :: y(m)
            logical, intent(in) :: grad
            force_ok = vok .or. .not. fresh
            if (force_ok) return
            force_ok = all(ieee_is_finite(y))
            if (force_ok) return
            if (grad) ks%ng = ks%ng - 1
            if (.not. grad) ks%nf = ks%nf - 1
            ! the model's fault only where the state it was evaluated at is finite
            call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                            fsym_all_finite(m, q)))
        end function force_ok

        !> Evaluate what `req` names, record it, accept it (checked when `check`); false
        !> when the step failed (undone) or was suspended.
        logical function evaluated(req, check)
            integer, intent(in) :: req
            logical, intent(in) :: check
            integer :: mst, kind
            mst = 0
            select case (req)
            case (REQ_FORCE)
                call model%acceleration(qp, a, mst); kind = EVAL_FORCE
            case (REQ_GRADIENT)
                call model%gradient(qp, a, g, mst); kind = EVAL_GRADIENT
            case default
                call model%acceleration(qe, ae, mst); kind = EVAL_EXTRAPOLATED
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
            evaluated = accepted(req, check)
        end function evaluated

        !> Mark a force put into its slot valid and count it; when `check`, first check it
        !> (false, step undone, if it is not finite).
        logical function accepted(req, check)
            integer, intent(in) :: req
            logical, intent(in) :: check
            integer :: slot
            accepted = .true.
            if (check) then
                slot = ks%ia
                if (req == REQ_GRADIENT) slot = ks%ig
                if (req == REQ_FORCE_SHIFTED) slot = ks%iae
                accepted = fsym_all_finite(m, w(:, :, slot))
                if (.not. accepted) then     ! the model's fault only where the state is finite
                    call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                                    fsym_all_finite(m, q) .and. fsym_all_finite(m, v)))
                    return
                end if
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


    end subroutine fsym_kernel_run

end module fsym_kernel
