!> A plain interpreter of a stage table with the model's own drift (`model%drift`), for the
!> Kepler-drift measurements (orders, the outer solar system) while the library's kernel
!> still does free flight at its drift stages. It takes the stages one by one, as the table
!> says (no first-same-as-last reuse: `evaluations_per_step` counts as the kernel would),
!> and stops at the first failure with the model's status. It is measurement code beside
!> the programs, not a second kernel: it keeps no cache, no undo and no counters.
module fsym_planets_split
    use fsym_kinds, only: wp, ik
    use fsym_force, only: force_model_t
    use fsym_scheme, only: scheme_t, OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    use fsym_planets, only: planets_model_t, PLANETS_JACOBI
    implicit none
    private

    public :: split_run, evaluations_per_step, fit_eps_exponents

    real(wp), parameter :: TWO_PI = 6.28318530717958647692528676655900577_wp

contains

    !> Take `nsteps` steps of size h of `scheme` from (q, v); `a`, `g`, `qe` are work arrays
    !> of the state's shape. `stat` is the model's status of the first failure (0: none) and
    !> `ndone` the steps completed before it.
    subroutine split_run(scheme, model, q, v, h, nsteps, a, g, qe, stat, ndone)
        type(scheme_t), intent(in) :: scheme                !! stage table
        class(force_model_t), intent(inout) :: model        !! model with its drift
        real(wp), intent(inout), contiguous :: q(:, :)      !! positions
        real(wp), intent(inout), contiguous :: v(:, :)      !! velocities
        real(wp), intent(in) :: h                           !! step
        integer(ik), intent(in) :: nsteps                   !! steps to take
        real(wp), intent(inout), contiguous :: a(:, :), g(:, :), qe(:, :)  !! work
        integer, intent(out) :: stat                        !! model status (0: success)
        integer(ik), intent(out) :: ndone                   !! steps completed
        integer :: k
        real(wp) :: c, u
        stat = 0
        do ndone = 0, nsteps - 1
            do k = 1, scheme%nop
                c = scheme%c(k)
                u = scheme%u(k)
                select case (scheme%op(k))
                case (OP_DRIFT)
                    call model%drift(q, v, c * h, stat)
                case (OP_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) v = v + (c * h) * a
                case (OP_GRAD_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) call model%gradient(q, a, g, stat)
                    if (stat == 0) v = v + (c * h) * a + (u * h**3) * g
                case (OP_EXTRAP_KICK)
                    call model%acceleration(q, a, stat)
                    if (stat == 0) then
                        qe = q + (u * h * h) * a
                        call model%acceleration(qe, g, stat)
                    end if
                    if (stat == 0) v = v + (c * h) * g
                case default
                    stat = -1   ! not an operation code of a valid table
                end select
                if (stat /= 0) return
            end do
        end do
        ndone = nsteps
    end subroutine split_run

    !> Force-equivalent evaluations per step, as the kernel counts them: forces with the
    !> first-same-as-last reuse plus gradients (a gradient counted as one).
    pure integer function evaluations_per_step(scheme)
        type(scheme_t), intent(in) :: scheme   !! stage table
        evaluations_per_step = scheme%nforce + scheme%ngrad
    end function evaluations_per_step

    !> Fitted exponents p, q of err = eps a(h) + eps^2 b(h), a ~ h^p, b ~ h^q, on two planets
    !> (Jacobi; masses eps and eps/2 at a = 1 and 2.5, 4 inner periods): with e(eps) the
    !> end-state error of the outer planet against SRKN6b at h/40, 4 e(eps) - e(2 eps) =
    !> 2 eps a and e(2 eps) - 2 e(eps) = 2 eps^2 b to O(eps^3); p and q from h = P/20 and
    !> P/40 at eps = 1e-3. `stat` is the first failing run's status (0: none).
    subroutine fit_eps_exponents(scheme, sref, p, q, stat)
        type(scheme_t), intent(in) :: scheme   !! the table to fit
        type(scheme_t), intent(in) :: sref     !! the reference table (SRKN6b)
        real(wp), intent(out) :: p             !! exponent of the eps term
        real(wp), intent(out) :: q             !! exponent of the eps^2 term
        integer, intent(out) :: stat           !! 0, or a run's failure
        real(wp), parameter :: EPS = 1.0e-3_wp
        real(wp) :: e1(6), e2(6), ea(2), eb(2)
        integer :: k
        do k = 1, 2
            call end_error(EPS, 20 * 2**(k - 1), e1, stat)
            if (stat /= 0) return
            call end_error(2.0_wp * EPS, 20 * 2**(k - 1), e2, stat)
            if (stat /= 0) return
            ea(k) = norm2(4.0_wp * e1 - e2)
            eb(k) = norm2(e2 - 2.0_wp * e1)
        end do
        p = log(ea(1) / ea(2)) / log(2.0_wp)
        q = log(eb(1) / eb(2)) / log(2.0_wp)
    contains
        subroutine end_error(eps, nper, e, st)
            real(wp), intent(in) :: eps
            integer, intent(in) :: nper
            real(wp), intent(out) :: e(6)
            integer, intent(out) :: st
            type(planets_model_t) :: md
            real(wp) :: x(3, 2), u(3, 2), xr(3, 2), ur(3, 2), a(3, 2), g(3, 2), xe(3, 2), h
            integer(ik) :: n, nd
            e = 0.0_wp
            call md%init(1.0_wp, [eps, 0.5_wp * eps], 1.0_wp, PLANETS_JACOBI, st)
            if (st /= 0) return
            x(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]; u(:, 1) = [0.0_wp, 1.05_wp, 0.02_wp]
            x(:, 2) = [0.0_wp, 2.5_wp, 0.05_wp]; u(:, 2) = [-0.65_wp, 0.0_wp, 0.0_wp]
            xr = x; ur = u
            n = 4 * nper
            h = 4.0_wp * TWO_PI / real(n, wp)
            call split_run(scheme, md, x, u, h, n, a, g, xe, st, nd)
            if (st /= 0) return
            call split_run(sref, md, xr, ur, h / 40.0_wp, 40 * n, a, g, xe, st, nd)
            e(1:3) = x(:, 2) - xr(:, 2)
            e(4:6) = u(:, 2) - ur(:, 2)
        end subroutine end_error
    end subroutine fit_eps_exponents

end module fsym_planets_split
