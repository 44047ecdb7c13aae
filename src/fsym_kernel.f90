!> The one splitting kernel: a loop over steps with the loop over the stage table inside,
!> calling the force model directly; it knows no model. Every face runs it (modern, F77,
!> reverse communication, C). State: `kernel_state_t` (`fsym_kernel_state`), work array
!> `w(d, n, nslot)` of the caller. A step never allocates and does no I/O; it completes or
!> leaves q, v bitwise as on entry (every force and new state checked for NaN/Inf; a model's
!> `stat` undoes it). The end-of-step force is reused while q is bitwise unchanged. A model's
!> `stat = KERNEL_SUSPEND` suspends the step (`ks%req`: the force the caller supplies).
module fsym_kernel
    use fsym_kinds, only: wp, ik, iwp
    use fsym_status
    use fsym_scheme, only: OP_DRIFT, OP_GRAD_KICK, OP_EXTRAP_KICK
    use fsym_force, only: force_model_t, recorder_t, EVAL_FORCE, EVAL_GRADIENT, &
                          EVAL_EXTRAPOLATED
    use fsym_kernel_state, only: kernel_state_t, KERNEL_SUSPEND, REQ_NONE, REQ_FORCE, &
        REQ_GRADIENT, REQ_FORCE_SHIFTED, fsym_kernel_layout, fsym_kernel_abort, &
        fsym_kernel_invalidate, fsym_kernel_entry, fsym_kernel_refused, fsym_kernel_keep
    use fsym_kernel_loops, only: fsym_all_finite, copy => fsym_loop_copy, &
        shifted => fsym_loop_shifted, update_comp => fsym_loop_update_comp, &
        update2_comp => fsym_loop_update2_comp, exchange => fsym_loop_exchange
    implicit none
    private

    public :: kernel_state_t, KERNEL_SUSPEND, REQ_NONE, REQ_FORCE, REQ_GRADIENT
    public :: REQ_FORCE_SHIFTED
    public :: fsym_kernel_layout, fsym_kernel_run, fsym_kernel_abort, fsym_kernel_invalidate
    public :: fsym_all_finite

contains

    !> Take up to `nsteps` steps of size h (or resume a suspended step and go on); `ndone`
    !> are complete. On failure `stat` is an `FSYM_ERR_*` code, q and v the state after
    !> `ndone` steps, `ks%pc` the failing stage (0: refused on entry, nop + 1: the new state).
    !> `stat = KERNEL_SUSPEND`: suspended (`ks%req`). `step0`: steps before, for the recorder.
    !> Every update tests its new values in the same loop; a force used by a kick is checked
    !> by that test (x + s y is NaN or Inf wherever y is), and a failed test looks at y to
    !> tell a non-finite force (the stage fails) from a non-finite state (the step fails at
    !> its end); other forces are checked at once. The first update of q and of v in a step
    !> saves the old values in the same loop, or, in a run of steps, writes into the other
    !> buffer of two (`sw`, swap mode): the state the step restores on failure; where the entry
    !> check found q bitwise in slot iqlast, that slot becomes iq0 (`qpre`): q is not saved.
    subroutine fsym_kernel_run(nop, op, c, u, model, ks, q, v, w, h, nsteps, ndone, stat, &
                               recorder, step0)
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
        real(wp), pointer, contiguous :: qp(:, :), a(:, :), g(:, :), x(:, :), qo(:, :), vc(:, :)
        real(wp), pointer, contiguous :: vo(:, :), tp(:, :)
        integer(ik) :: i, s0, nlast
        integer :: k, m, iy, iyf, mst
        real(wp) :: hs, shift
        logical :: qok, vok, vwas, fresh, fa, resumed, teed, two, rec, lazy, sw, qpre

        ndone = 0; stat = FSYM_SUCCESS; m = ks%d * ks%n; s0 = 0; teed = .false.; lazy = .false.
        if (present(step0)) s0 = step0
        rec = present(recorder); qpre = .false.
        qp => q; a => w(:, :, ks%ia); g => w(:, :, ks%ig)      ! descriptors made once
        ! swap mode (`sw`, runs of steps on 64 values or more): a step's first update of q (v)
        ! writes into the other buffer (current: qp, vc), the start stays; `settle` ends it
        sw = nsteps > 1 .and. m >= 64 .and. .not. (ks%comp .or. ks%active)
        qo => w(:, :, ks%iq0); vc => v; vo => w(:, :, ks%iv0)
        if (.not. ks%active) then
            if (nsteps < 1) return
            ks%pc = 0
            if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) then
                stat = FSYM_ERR_BAD_STEP; return
            end if
            lazy = op(1) == OP_DRIFT .and. .not. ks%comp    ! the first drift is the check
            if (.not. lazy) then
                if (.not. fsym_kernel_entry(op(1), ks, q, v, w, lazy)) then   ! q, v finite?
                    stat = FSYM_ERR_NONFINITE_STATE; return
                end if
                qpre = lazy      ! q is bitwise in slot iqlast, the cached force's point
            end if
        end if
        hs = h; nlast = max(nsteps, 1_ik)
        steps: do i = 1, nlast
            qok = .true.; vok = .true.; resumed = ks%active
            if (resumed) then
                ! resume: the caller has put the requested force into its slot
                hs = ks%h
                if (.not. accepted(ks%req, .true.)) return
                ks%active = .false.; ks%req = REQ_NONE
            else
                ks%qsaved = ks%comp; ks%vsaved = ks%comp      ! compensated: all saved here
                if (ks%comp) call fsym_kernel_keep(ks, q, v, w)
                ks%h = hs; ks%pc = 1
            end if
            do k = ks%pc, nop
                if (lazy .and. k == 2) then     ! the first update has checked the entry
                    lazy = .false.
                    if (.not. (qok .and. vok)) then
                        call settle()
                        if (fsym_kernel_refused(op(1), ks, q, v, w)) then
                            stat = FSYM_ERR_NONFINITE_STATE; return
                        end if
                    end if
                end if
                ks%pc = k
                if (op(k) == OP_DRIFT) then
                    if (qpre .and. .not. ks%qsaved) then   ! slot iqlast holds q: now iq0
                        iy = ks%iq0; ks%iq0 = ks%iqlast; ks%iqlast = iy; ks%qsaved = .true.
                        qo => w(:, :, ks%iq0)
                    end if
                    qpre = .false.
                    teed = i == nlast .and. k == ks%klast .and. .not. (ks%comp .or. lazy)  ! iqlast
                    qok = upd(qp, w(:, :, ks%iqc), qo, c(k) * hs, vc, 0.0_wp, vc, .false., &
                              ks%qsaved, w(:, :, ks%iqlast), teed)
                    if (sw .and. .not. ks%qsaved) then; tp => qp; qp => qo; qo => tp; end if
                    ks%qsaved = .true.
                    ks%have_a = .false.; ks%have_g = .false.; ks%have_x = .false.
                    cycle
                end if
                ! a kick: the forces it needs (slot iy; iyf: the one evaluated for it; common
                ! path inline, the rest in `noted`), the update
                fa = .not. ks%have_a; iy = ks%ia; iyf = ks%ia
                if (fa) then
                    mst = 0; call model%acceleration(qp, a, mst)
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
                        mst = 0; call model%gradient(qp, a, g, mst)
                        if (mst /= 0 .or. rec) then
                            if (.not. noted(REQ_GRADIENT, mst, .false.)) return
                        else
                            ks%have_g = .true.; ks%ng = ks%ng + 1
                        end if
                    end if
                case (OP_EXTRAP_KICK)
                    shift = u(k) * hs * hs; iy = ks%iae; iyf = ks%iae; fa = .false.
                    fresh = .not. ks%have_x .or. ks%xshift /= shift
                    if (fresh) then
                        call shifted(m, qp, shift, a, w(:, :, ks%iqe))
                        ks%xshift = shift; ks%have_x = .false.; mst = 0
                        call model%acceleration(w(:, :, ks%iqe), w(:, :, ks%iae), mst)
                        if (.not. noted(REQ_FORCE_SHIFTED, mst, .false.)) return
                    end if
                case default
                    fresh = fa; fa = .false.
                end select
                vwas = vok
                two = op(k) == OP_GRAD_KICK
                vok = upd(vc, w(:, :, ks%ivc), vo, c(k) * hs, w(:, :, iy), u(k) * hs**3, g, two, &
                          ks%vsaved, w(:, :, ks%iqlast), .false.)
                if (sw .and. .not. ks%vsaved) then; tp => vc; vc => vo; vo => tp; end if
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
        if (sw) call settle()
        if (ks%have_a .and. .not. teed) call copy(m, q, w(:, :, ks%iqlast))

    contains

        !> x <- x + s y, or x + (s y + r y2) when `two` (compensated in e when `ks%comp`), the
        !> old x into x0 unless `saved`; in swap mode the first update writes the new x into
        !> x0 instead (x kept). The new x into z when `tee`; true when all finite.
        logical function upd(x, e, x0, s, y, r, y2, two, saved, z, tee) result(ok)
            real(wp), intent(inout) :: x(m), e(m), x0(m), z(m)
            real(wp), intent(in) :: s, y(m), r, y2(m)
            logical, intent(in) :: two, saved, tee
            real(wp) :: t
            integer :: j
            integer(iwp) :: bad
            if (ks%comp) then
                if (two) ok = update2_comp(m, x, e, s, y, r, y2)
                if (.not. two) ok = update_comp(m, x, e, s, y)
                return
            end if
            bad = 0
            if (sw .and. .not. saved) then
                do j = 1, m
                    if (two) x0(j) = x(j) + (s * y(j) + r * y2(j))
                    if (.not. two) x0(j) = x(j) + s * y(j)
                    bad = ior(bad, transfer(x0(j) - x0(j), bad))
                    if (tee) z(j) = x0(j)
                end do
            else
                do j = 1, m
                    t = x(j)
                    if (two) x(j) = t + (s * y(j) + r * y2(j))
                    if (.not. two) x(j) = t + s * y(j)
                    bad = ior(bad, transfer(x(j) - x(j), bad))    ! see fsym_kernel_loops
                    if (.not. saved) x0(j) = t
                    if (tee) z(j) = x(j)
                end do
            end if
            ok = iand(bad, huge(bad)) == 0
        end function upd

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
                            fsym_all_finite(m, qp) .and. (vwas .or. fy)))
        end function forces_ok

        !> After an evaluation with a recorder, a non-zero model `stat` or a force to `check`:
        !> record the point, accept the force (`accepted`); false when the model suspended
        !> the step or failed, or the force is not finite (the step undone).
        logical function noted(req, mst, check)
            integer, intent(in) :: req, mst
            logical, intent(in) :: check
            noted = .false.
            if (mst == KERNEL_SUSPEND) then
                call settle()
                ks%active = .true.; ks%req = req; stat = KERNEL_SUSPEND
                return
            end if
            if (present(recorder)) then
                x => qp
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
                call settle()
                call fail(merge(FSYM_ERR_NONFINITE_FORCE, FSYM_ERR_NONFINITE_STATE, &
                                fsym_all_finite(m, q) .and. fsym_all_finite(m, v)))
            else if (req == REQ_GRADIENT) then
                ks%have_g = .true.; ks%ng = ks%ng + 1
            else
                ks%have_a = ks%have_a .or. req == REQ_FORCE; ks%nf = ks%nf + 1
                ks%have_x = ks%have_x .or. req == REQ_FORCE_SHIFTED
            end if
        end function accepted

        !> End swap mode: the current state into the caller's arrays, the state of the step's
        !> start into slots iq0, iv0 (as saved without swap mode).
        subroutine settle()
            if (.not. sw) return
            if (.not. associated(qp, q)) call exchange(m, q, qp)
            if (.not. associated(vc, v)) call exchange(m, v, vc)
            qp => q; qo => w(:, :, ks%iq0); vc => v; vo => w(:, :, ks%iv0); sw = .false.
        end subroutine settle

        !> Undo the step in progress and report `code`.
        subroutine fail(code)
            integer, intent(in) :: code
            call settle()
            ks%active = .true.
            call fsym_kernel_abort(ks, q, v, w)
            stat = code
        end subroutine fail

    end subroutine fsym_kernel_run

end module fsym_kernel
