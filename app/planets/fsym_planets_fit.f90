!> The fit of the two error exponents of a Kepler-drift table (err = eps a(h) + eps^2 b(h)) on
!> two planets, every run through the library's integrator (`integrator_t`: the one kernel,
!> the model's Kepler drift at its drift stages), and the evaluations a table costs per step.
module fsym_planets_fit
    use fsym_kinds, only: wp, ik
    use fsym_integrator, only: integrator_t
    use fsym_scheme, only: scheme_t, OP_DRIFT
    use fsym_planets, only: planets_model_t, PLANETS_JACOBI
    implicit none
    private

    public :: evaluations_per_step, fit_eps_exponents, kick_quadrature

    real(wp), parameter :: TWO_PI = 6.28318530717958647692528676655900577_wp

contains

    !> Force-equivalent evaluations per step, as the kernel counts them: forces with the
    !> first-same-as-last reuse plus gradients (a gradient counted as one).
    pure integer function evaluations_per_step(scheme)
        type(scheme_t), intent(in) :: scheme   !! stage table
        evaluations_per_step = scheme%nforce + scheme%ngrad
    end function evaluations_per_step

    !> The quadrature of a table's kicks along the drift (nodes: the summed drift weights before
    !> each kick; weights: the kick weights): its order K (the first moment that is not exact,
    !> to 1e-12; at most 13) and the error of that moment, sum b_i t_i^K - 1/(K + 1). To first
    !> order in eps a Kepler-drift step integrates the interaction along the Kepler flow by this
    !> rule, so K is the h exponent of the eps-linear error and the moment error its size.
    pure subroutine kick_quadrature(scheme, order, moment_error)
        type(scheme_t), intent(in) :: scheme   !! stage table
        integer, intent(out) :: order          !! the rule's order K
        real(wp), intent(out) :: moment_error  !! sum b_i t_i^K - 1/(K + 1)
        real(wp) :: t
        integer :: j
        do order = 0, 12
            t = 0.0_wp; moment_error = -1.0_wp / real(order + 1, wp)
            do j = 1, scheme%nop
                if (scheme%op(j) == OP_DRIFT) then
                    t = t + scheme%c(j)
                else
                    moment_error = moment_error + scheme%c(j) * t**order
                end if
            end do
            if (abs(moment_error) > 1.0e-12_wp) return
        end do
    end subroutine kick_quadrature

    !> Fitted exponents p, q of err = eps a(h) + eps^2 b(h), a ~ h^p, b ~ h^q, on two planets
    !> (Jacobi; masses eps and eps/2 at a = 1 and 2.5, 4 inner periods): with e(eps) the
    !> end-state error of the outer planet against SRKN6b at h/40, 4 e(eps) - e(2 eps) =
    !> 2 eps a and e(2 eps) - 2 e(eps) = 2 eps^2 b to O(eps^3); p and q from h = P/20 and
    !> P/40 at eps = 1e-2 (or from P/`nper` and P/(2 `nper`), at `eps`). At eps = 1e-2 the
    !> eps^2 part of the tables with small errors (BM, BM-mf) stands well above rounding (at
    !> 1e-3 BM-mf's q came out 3.81), and the O(eps^3) rest stays small: every fourth-order
    !> table within 0.08 of 4. `stat` is the first failing run's status (0: none).
    subroutine fit_eps_exponents(scheme, sref, p, q, stat, nper, eps)
        type(scheme_t), intent(in) :: scheme   !! the table to fit
        type(scheme_t), intent(in) :: sref     !! the reference table (SRKN6b)
        real(wp), intent(out) :: p             !! exponent of the eps term
        real(wp), intent(out) :: q             !! exponent of the eps^2 term
        integer, intent(out) :: stat           !! 0, or a run's failure
        integer, intent(in), optional :: nper  !! the larger step is P/nper (default 20)
        real(wp), intent(in), optional :: eps  !! the smaller mass ratio (default 1e-2)
        real(wp) :: e0
        real(wp) :: e1(6), e2(6), ea(2), eb(2)
        integer :: k, n0
        n0 = 20; e0 = 1.0e-2_wp
        if (present(nper)) n0 = nper
        if (present(eps)) e0 = eps
        do k = 1, 2
            call end_error(e0, n0 * 2**(k - 1), e1, stat)
            if (stat /= 0) return
            call end_error(2.0_wp * e0, n0 * 2**(k - 1), e2, stat)
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
            type(integrator_t) :: it, ref
            real(wp) :: x(3, 2), u(3, 2), xr(3, 2), ur(3, 2), h
            integer(ik) :: n
            e = 0.0_wp
            call md%init(1.0_wp, [eps, 0.5_wp * eps], 1.0_wp, PLANETS_JACOBI, st)
            if (st /= 0) return
            x(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]; u(:, 1) = [0.0_wp, 1.05_wp, 0.02_wp]
            x(:, 2) = [0.0_wp, 2.5_wp, 0.05_wp]; u(:, 2) = [-0.65_wp, 0.0_wp, 0.0_wp]
            xr = x; ur = u
            n = 4 * nper
            h = 4.0_wp * TWO_PI / real(n, wp)
            call it%init(scheme, md, 3, 2, st)
            if (st == 0) call it%run(md, x, u, h, n, st)
            if (st /= 0) return
            call ref%init(sref, md, 3, 2, st)
            if (st == 0) call ref%run(md, xr, ur, h / 40.0_wp, 40 * n, st)
            e(1:3) = x(:, 2) - xr(:, 2)
            e(4:6) = u(:, 2) - ur(:, 2)
        end subroutine end_error
    end subroutine fit_eps_exponents

end module fsym_planets_fit
