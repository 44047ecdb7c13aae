!> The harmonic oscillator V = omega^2 q^2/2 under a splitting scheme, from its data alone
!> (no LAPACK): one step is a 2x2 map of (q, v/omega) whose entries are polynomials in
!> x = h omega, built from the stage arrays: a drift is [[1, c x], [0, 1]], a kick
!> [[1, 0], [-c x, 1]], a gradient kick adds 2 u x^3 (g = grad|a|^2 = 2 omega^4 q), an
!> extrapolated kick uses a(q + u h^2 a) = -omega^2 (1 - u x^2) q. Every stage has
!> determinant 1, so the map is stable while |trace| < 2; x* is the end of the first such
!> interval. The stability study and the step-size guard of the integrator both use it.
module fsym_oscillator
    use fsym_kinds, only: wp
    use fsym_scheme, only: scheme_t, OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
    implicit none
    private

    public :: fsym_oscillator_map, fsym_oscillator_trace, fsym_stability_interval

    real(wp), parameter :: default_xmax = 40.0_wp   !! scan range of x for the interval
    real(wp), parameter :: default_dx = 1.0e-3_wp   !! scan resolution of x

contains

    !> The oscillator step map of `scheme` at x = h omega, acting on (q, v/omega).
    pure subroutine fsym_oscillator_map(scheme, x, m)
        type(scheme_t), intent(in) :: scheme  !! any splitting scheme
        real(wp), intent(in) :: x             !! h omega
        real(wp), intent(out) :: m(2, 2)      !! the map
        real(wp) :: s
        integer :: k
        m = reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2])
        do k = 1, scheme%nop
            select case (scheme%op(k))
            case (OP_DRIFT)
                m(1, :) = m(1, :) + scheme%c(k) * x * m(2, :)
                cycle
            case (OP_KICK)
                s = -scheme%c(k) * x
            case (OP_GRAD_KICK)
                s = -scheme%c(k) * x + 2.0_wp * scheme%u(k) * x**3
            case (OP_EXTRAP_KICK)
                s = -scheme%c(k) * x * (1.0_wp - scheme%u(k) * x**2)
            case default
                s = 0.0_wp
            end select
            m(2, :) = m(2, :) + s * m(1, :)
        end do
    end subroutine fsym_oscillator_map

    !> Trace of the oscillator step map at x = h omega.
    pure real(wp) function fsym_oscillator_trace(scheme, x)
        type(scheme_t), intent(in) :: scheme  !! any splitting scheme
        real(wp), intent(in) :: x             !! h omega
        real(wp) :: m(2, 2)
        call fsym_oscillator_map(scheme, x, m)
        fsym_oscillator_trace = m(1, 1) + m(2, 2)
    end function fsym_oscillator_trace

    !> Stability interval (0, x*) of `scheme` on the oscillator: a scan of |trace| < 2 with
    !> step `dx` (default 1e-3) up to `xmax` (default 40), then bisection to round-off on the
    !> first bracket where |trace| reaches 2. x* = xmax when no end is found in the range.
    !> Where the trace meets -2 or 2 with zero slope (A: trace + 2 = -(x^2 - 12)^3/432),
    !> round-off in the trace limits x* to about 1e-5 relative.
    !> `xnext`: the first scan point beyond x* where |trace| < 2 again (end of the first
    !> instability window), xmax if none.
    pure subroutine fsym_stability_interval(scheme, xstar, xmax, dx, xnext)
        type(scheme_t), intent(in) :: scheme      !! any splitting scheme
        real(wp), intent(out) :: xstar            !! end of the stability interval
        real(wp), intent(in), optional :: xmax    !! scan range
        real(wp), intent(in), optional :: dx      !! scan resolution
        real(wp), intent(out), optional :: xnext  !! end of the first instability window
        real(wp) :: top, step, lo, hi, mid
        integer :: k, nscan, j
        top = default_xmax; step = default_dx
        if (present(xmax)) top = xmax
        if (present(dx)) step = dx
        nscan = max(1, ceiling(top / step))
        xstar = top
        if (present(xnext)) xnext = top
        lo = 0.0_wp
        do k = 1, nscan
            hi = k * step
            if (.not. (abs(fsym_oscillator_trace(scheme, hi)) < 2.0_wp)) then
                do while (hi - lo > 4.0_wp * epsilon(1.0_wp) * hi)
                    mid = 0.5_wp * (lo + hi)
                    if (abs(fsym_oscillator_trace(scheme, mid)) < 2.0_wp) then
                        lo = mid
                    else
                        hi = mid
                    end if
                end do
                xstar = lo
                if (present(xnext)) then
                    do j = k + 1, nscan
                        if (abs(fsym_oscillator_trace(scheme, j * step)) < 2.0_wp) then
                            xnext = j * step
                            exit
                        end if
                    end do
                end if
                return
            end if
            lo = hi
        end do
    end subroutine fsym_stability_interval

end module fsym_oscillator
