!> Checks for users who test their own force models, with pFUnit or any other framework:
!>
!>  - `fsym_check_gradient` compares a model's gradient term with central finite differences
!>    of sum_i m_i |a_i|^2 (for unit masses the paper's grad |F|^2) and returns the worst
!>    relative error and the component where it occurs;
!>  - `fsym_check_order` measures the order of a method on a model: runs over the same time
!>    with n, 2n, 4n, ... steps, and the ratios of the differences between successive runs
!>    (no exact solution needed).
!>
!> Both allocate their work arrays (they are test tools, not time steps) and report errors
!> through optional `stat`/`errmsg` (codes from `fsym_status`).
module fsym_checks
    use fsym_kinds, only: wp, ik
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_BAD_PARAMETER, &
                           FSYM_ERR_NO_GRADIENT, FSYM_ERR_MODEL, FSYM_ERR_NONFINITE_FORCE, &
                           FSYM_ERR_NO_CONVERGENCE, fsym_report, fsym_pass, fsym_int_text
    use fsym_force, only: force_model_t
    use fsym_stepper, only: stepper_t
    use fsym_methods, only: fsym_new_stepper
    implicit none
    private
    public :: fsym_check_gradient, fsym_check_order

contains

    !> Compare the gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2 that `model` returns
    !> at q with central finite differences (increment delta * max(1, |q_kj|), default delta
    !> = 1e-5). `worst` is the largest |g - fd| / max(|fd|, 1e-3 max|fd|) over all components
    !> (relative to the component, or to a thousandth of the largest one where the component
    !> is smaller), found at `where` = (dimension, particle). Typical values for a correct
    !> gradient are 1e-9..1e-7; a wrong factor or sign shows as 1e-2 or more.
    subroutine fsym_check_gradient(model, q, worst, where, stat, errmsg, masses, delta)
        class(force_model_t), intent(inout) :: model          !! the model under test
        real(wp), intent(in) :: q(:, :)                       !! positions (d, n)
        real(wp), intent(out) :: worst                        !! worst relative error
        integer, intent(out) :: where(2)                      !! its (dimension, particle)
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp), intent(in), optional :: masses(:)           !! m_i (default: all 1)
        real(wp), intent(in), optional :: delta               !! relative increment
        real(wp), allocatable :: qq(:, :), a(:, :), g(:, :), fd(:, :), m(:)
        real(wp) :: del, dq, sp, sm, floor, err
        integer :: d, n, j, k, st

        worst = huge(1.0_wp)
        where = 0
        d = size(q, 1); n = size(q, 2)
        if (d < 1 .or. n < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'q must be (d, n) with d, n >= 1', stat, errmsg)
            return
        end if
        allocate (m(n))
        m = 1.0_wp
        if (present(masses)) then
            if (size(masses) /= n) then
                call fsym_report(FSYM_ERR_SHAPE, 'masses must have one entry per particle', &
                                 stat, errmsg)
                return
            end if
            if (.not. all(masses > 0.0_wp .and. masses <= huge(1.0_wp))) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, 'masses must be positive and finite', &
                                 stat, errmsg)
                return
            end if
            m = masses
        end if
        del = 1.0e-5_wp
        if (present(delta)) then
            if (.not. (delta > 0.0_wp .and. delta < 1.0_wp)) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, 'delta must be in (0, 1)', stat, errmsg)
                return
            end if
            del = delta
        end if
        if (.not. model%has_gradient()) then
            call fsym_report(FSYM_ERR_NO_GRADIENT, 'the model has no gradient term', stat, errmsg)
            return
        end if

        allocate (qq(d, n), a(d, n), g(d, n), fd(d, n))
        qq = q
        st = 0
        call model%acceleration(qq, a, st)
        if (st == 0) call model%gradient(qq, a, g, st)
        if (st /= 0) then
            call fsym_report(FSYM_ERR_MODEL, 'the model failed at q (its status ' // &
                             fsym_int_text(st)//')', stat, errmsg)
            return
        end if
        do j = 1, n
            do k = 1, d
                dq = del * max(1.0_wp, abs(q(k, j)))
                qq(k, j) = q(k, j) + dq
                call weighted_square(model, qq, m, a, sp, st)
                if (st /= 0) exit
                qq(k, j) = q(k, j) - dq
                call weighted_square(model, qq, m, a, sm, st)
                if (st /= 0) exit
                qq(k, j) = q(k, j)
                fd(k, j) = (sp - sm) / (2.0_wp * dq * m(j))
            end do
            if (st /= 0) exit
        end do
        if (st /= 0) then
            call fsym_report(FSYM_ERR_MODEL, 'the model failed near q (its status ' // &
                             fsym_int_text(st)//')', stat, errmsg)
            return
        end if
        if (.not. (all(abs(fd) <= huge(1.0_wp)) .and. all(abs(g) <= huge(1.0_wp)))) then
            call fsym_report(FSYM_ERR_NONFINITE_FORCE, 'gradient term or its finite '// &
                             'differences not finite', stat, errmsg)
            return
        end if

        floor = max(1.0e-3_wp * maxval(abs(fd)), tiny(1.0_wp))
        worst = 0.0_wp
        where = [1, 1]
        do j = 1, n
            do k = 1, d
                err = abs(g(k, j) - fd(k, j)) / max(abs(fd(k, j)), floor)
                if (err > worst) then
                    worst = err
                    where = [k, j]
                end if
            end do
        end do
        call fsym_report(FSYM_SUCCESS, '', stat, errmsg)
    end subroutine fsym_check_gradient

    !> S = sum_i m_i |a_i(q)|^2 (a is work space).
    subroutine weighted_square(model, q, m, a, s, st)
        class(force_model_t), intent(inout) :: model  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions
        real(wp), intent(in) :: m(:)                  !! masses
        real(wp), intent(inout), contiguous :: a(:, :) !! work: accelerations at q
        real(wp), intent(out) :: s                    !! the weighted sum
        integer, intent(out) :: st                    !! the model's status
        integer :: j
        st = 0
        s = 0.0_wp
        call model%acceleration(q, a, st)
        if (st /= 0) return
        do j = 1, size(q, 2)
            s = s + m(j) * sum(a(:, j)**2)
        end do
    end subroutine weighted_square

    !> Measured order of `method` on `model`: `levels` runs (default 4, at least 3) from
    !> (q0, v0) over the time `t_end` with nsteps, 2 nsteps, 4 nsteps, ... steps.
    !> differences(k) = max |z_k - z_(k+1)| over all components of (q, v) of runs k and k+1,
    !> orders(k) = log2(differences(k) / differences(k+1)), and `order` the last of them (the
    !> finest pair). Choose nsteps so that the runs are in the asymptotic regime and the
    !> finest differences stay well above round-off (relative 1e-13 or more).
    subroutine fsym_check_order(method, model, q0, v0, t_end, nsteps, order, stat, errmsg, &
                                levels, differences, orders)
        character(len=*), intent(in) :: method                !! method label, e.g. `A`
        class(force_model_t), intent(inout) :: model          !! the model under test
        real(wp), intent(in) :: q0(:, :)                      !! initial positions (d, n)
        real(wp), intent(in) :: v0(:, :)                      !! initial velocities (d, n)
        real(wp), intent(in) :: t_end                         !! length of every run
        integer, intent(in) :: nsteps                         !! steps of the coarsest run
        real(wp), intent(out) :: order                        !! measured order, finest pair
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer, intent(in), optional :: levels               !! number of runs (>= 3)
        real(wp), intent(out), optional :: differences(:)     !! (levels - 1) differences
        real(wp), intent(out), optional :: orders(:)          !! (levels - 2) orders
        class(stepper_t), allocatable :: s
        real(wp), allocatable :: q(:, :), v(:, :), zprev(:), z(:), dif(:)
        integer :: nlev, k, st
        integer(ik) :: nk
        character(len=256) :: msg

        order = 0.0_wp
        nlev = 4
        if (present(levels)) nlev = levels
        if (nlev < 3 .or. nlev > 30) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'levels must be 3..30', stat, errmsg)
            return
        end if
        if (nsteps < 1 .or. .not. (abs(t_end) > 0.0_wp .and. abs(t_end) <= huge(1.0_wp))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'nsteps >= 1 and a finite t_end /= 0 '// &
                             'needed', stat, errmsg)
            return
        end if
        if (any(shape(v0) /= shape(q0)) .or. size(q0) < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'q0 and v0 must both be (d, n)', stat, errmsg)
            return
        end if
        if (present(differences)) then
            if (size(differences) < nlev - 1) then
                call fsym_report(FSYM_ERR_SHAPE, 'differences needs levels - 1 entries', &
                                 stat, errmsg)
                return
            end if
            differences = 0.0_wp
        end if
        if (present(orders)) then
            if (size(orders) < nlev - 2) then
                call fsym_report(FSYM_ERR_SHAPE, 'orders needs levels - 2 entries', stat, errmsg)
                return
            end if
            orders = 0.0_wp
        end if

        allocate (q, source=q0)
        allocate (v, source=v0)
        allocate (zprev(2 * size(q0)), z(2 * size(q0)), dif(nlev - 1))
        do k = 1, nlev
            q = q0; v = v0
            nk = int(nsteps, ik) * 2_ik**(k - 1)
            call fsym_new_stepper(method, model, size(q0, 1), size(q0, 2), s, st, msg)
            if (st == FSYM_SUCCESS) call s%run(model, q, v, t_end / real(nk, wp), nk, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, trim(msg)//' (run with '//fsym_int_text(nk)//' steps)', &
                               stat, errmsg)
                return
            end if
            z(1:size(q)) = reshape(q, [size(q)])
            z(size(q) + 1:) = reshape(v, [size(v)])
            if (k > 1) dif(k - 1) = maxval(abs(z - zprev))
            zprev = z
        end do
        if (present(differences)) differences(1:nlev - 1) = dif
        if (.not. all(dif > 0.0_wp)) then
            call fsym_report(FSYM_ERR_NO_CONVERGENCE, 'two runs gave the same result: the '// &
                             'differences are at round-off; use fewer steps', stat, errmsg)
            return
        end if
        do k = 1, nlev - 2
            order = log(dif(k) / dif(k + 1)) / log(2.0_wp)
            if (present(orders)) orders(k) = order
        end do
        call fsym_report(FSYM_SUCCESS, '', stat, errmsg)
    end subroutine fsym_check_order

end module fsym_checks
