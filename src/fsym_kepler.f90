!> Kepler problem in any dimension, H = |v|^2/2 - mu/|q|: acceleration, gradient term,
!> potential, energy, angular momentum, Laplace-Runge-Lenz vector, orbital elements and
!> period, the exact solution at time t (Kepler's equation) and the benchmark orbit of the
!> paper. Scalar physics is pure; `kepler_model_t` is the force model for `n` independent
!> bodies about a fixed centre (columns of q).
module fsym_kepler
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status
    use fsym_force, only: force_model_t
    implicit none
    private

    real(wp), parameter, public :: FSYM_PI = 3.14159265358979323846264338327950288_wp  !! pi

    ! bodies per block of `kepler_field` and `kepler_field_gradient`
    integer, parameter :: FIELD_BLOCK = 64
    ! fewer bodies than this (d = 2, 3) take one fused pass
    integer, parameter :: FIELD_FUSED_BELOW = 8
    ! bodies per chunk of the OpenMP threads over independent bodies (when built with OpenMP)
    integer, parameter :: OMP_CHUNK = 256

    !> Kepler force model: each column of q is a body attracted by mu at the origin.
    type, extends(force_model_t), public :: kepler_model_t
        real(wp) :: mu = 1.0_wp   !! gravitational parameter G M
    contains
        procedure :: acceleration => kepler_model_acceleration  !! -mu q/|q|^3 per column
        procedure :: gradient => kepler_model_gradient  !! grad |a|^2 per column
        procedure :: has_gradient => kepler_model_has_gradient  !! true
        procedure :: potential => kepler_model_potential  !! sum of -mu/|q_j|
        procedure :: has_potential => kepler_model_provides  !! true
        procedure :: local_frequency => kepler_model_frequency  !! max 2 mu / r^3 over bodies
        procedure :: has_frequency => kepler_model_provides  !! true
    end type kepler_model_t

    public :: kepler_acceleration, kepler_gradient, kepler_potential, kepler_energy
    public :: kepler_lrl, kepler_angular_momentum_2d, kepler_angular_momentum_sq
    public :: kepler_elements, kepler_period, kepler_exact, kepler_paper_orbit
    public :: kepler_elliptic_orbit, kepler_lrl_angle, kepler_field, kepler_field_gradient

contains

    !> Acceleration a = -mu q/|q|^3 of one body, q of any dimension.
    pure subroutine kepler_acceleration(q, a, mu)
        real(wp), intent(in) :: q(:)              !! position
        real(wp), intent(out) :: a(:)             !! acceleration
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: r2
        r2 = sum(q**2)
        a = -(opt_mu(mu) / (r2 * sqrt(r2))) * q
    end subroutine kepler_acceleration

    !> Gradient term grad |a|^2 = -4 mu^2 q/|q|^6 of one body.
    pure subroutine kepler_gradient(q, g, mu)
        real(wp), intent(in) :: q(:)              !! position
        real(wp), intent(out) :: g(:)             !! grad |a|^2
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: r2
        r2 = sum(q**2)
        g = -(4.0_wp * opt_mu(mu)**2 / r2**3) * q
    end subroutine kepler_gradient

    !> Potential energy -mu/|q|.
    pure real(wp) function kepler_potential(q, mu)
        real(wp), intent(in) :: q(:)              !! position
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        kepler_potential = -opt_mu(mu) / sqrt(sum(q**2))
    end function kepler_potential

    !> Energy |v|^2/2 - mu/|q|.
    pure real(wp) function kepler_energy(q, v, mu)
        real(wp), intent(in) :: q(:), v(:)        !! position, velocity
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        kepler_energy = 0.5_wp * sum(v**2) + kepler_potential(q, mu)
    end function kepler_energy

    !> Planar angular momentum x v_y - y v_x (2D).
    pure real(wp) function kepler_angular_momentum_2d(q, v)
        real(wp), intent(in) :: q(2), v(2)        !! position, velocity
        kepler_angular_momentum_2d = q(1) * v(2) - q(2) * v(1)
    end function kepler_angular_momentum_2d

    !> |L|^2 = |q|^2 |v|^2 - (q.v)^2, valid in any dimension.
    pure real(wp) function kepler_angular_momentum_sq(q, v)
        real(wp), intent(in) :: q(:), v(:)        !! position, velocity
        kepler_angular_momentum_sq = sum(q**2) * sum(v**2) - dot_product(q, v)**2
    end function kepler_angular_momentum_sq

    !> Laplace-Runge-Lenz vector A = v x L - mu q/|q| = q (|v|^2 - mu/|q|) - v (q.v), any
    !> dimension; it points to the pericentre and has length mu e.
    pure subroutine kepler_lrl(q, v, lrl, mu)
        real(wp), intent(in) :: q(:), v(:)        !! position, velocity
        real(wp), intent(out) :: lrl(:)           !! the LRL vector
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        lrl = q * (sum(v**2) - opt_mu(mu) / sqrt(sum(q**2))) - v * dot_product(q, v)
    end subroutine kepler_lrl

    !> Direction angle atan2(A_y, A_x) of the LRL vector of a planar (2D) state.
    pure real(wp) function kepler_lrl_angle(q, v, mu)
        real(wp), intent(in) :: q(2), v(2)        !! position, velocity
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: lrl(2)
        call kepler_lrl(q, v, lrl, mu)
        kepler_lrl_angle = atan2(lrl(2), lrl(1))
    end function kepler_lrl_angle

    !> Semi-major axis, eccentricity and period of a bound state.
    pure subroutine kepler_elements(q, v, a, e, period, stat, mu)
        real(wp), intent(in) :: q(:), v(:)        !! position, velocity
        real(wp), intent(out) :: a                !! semi-major axis
        real(wp), intent(out) :: e                !! eccentricity
        real(wp), intent(out) :: period           !! orbital period
        integer, intent(out) :: stat              !! FSYM_ERR_NOT_ELLIPTIC unless bound
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: en, m, lrl(size(q))
        m = opt_mu(mu)
        en = kepler_energy(q, v, m)
        a = 0.0_wp; e = 0.0_wp; period = 0.0_wp
        if (.not. (en < 0.0_wp) .or. fsym_same(sum(q**2), 0.0_wp)) then
            stat = FSYM_ERR_NOT_ELLIPTIC; return
        end if
        a = -m / (2.0_wp * en)
        call kepler_lrl(q, v, lrl, m)
        e = sqrt(sum(lrl**2)) / m
        period = 2.0_wp * FSYM_PI * sqrt(a**3 / m)
        stat = FSYM_SUCCESS
    end subroutine kepler_elements

    !> Period 2 pi sqrt(a^3/mu) of a bound state (0 if unbound).
    pure real(wp) function kepler_period(q, v, mu)
        real(wp), intent(in) :: q(:), v(:)        !! position, velocity
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: a, e
        integer :: st
        call kepler_elements(q, v, a, e, kepler_period, st, mu)
    end function kepler_period

    !> Exact state at time t of the bound orbit through (q0, v0), any dimension, by Kepler's
    !> equation (Newton iteration) and the f and g functions.
    pure subroutine kepler_exact(q0, v0, t, q, v, stat, mu)
        real(wp), intent(in) :: q0(:), v0(:)      !! state at time 0
        real(wp), intent(in) :: t                 !! time
        real(wp), intent(out) :: q(:), v(:)       !! state at time t
        integer, intent(out) :: stat              !! FSYM_SUCCESS, NOT_ELLIPTIC, NO_CONVERGENCE
        real(wp), intent(in), optional :: mu      !! G M (default 1)
        real(wp) :: m, a, e, period, r0, nmean, ecosE0, esinE0, E0, M0, Mt, EE, dE, f, g
        real(wp) :: fdot, gdot, r, tred, dEk
        integer :: it
        m = opt_mu(mu)
        q = q0; v = v0
        call kepler_elements(q0, v0, a, e, period, stat, m)
        if (stat /= FSYM_SUCCESS) return
        r0 = sqrt(sum(q0**2))
        nmean = sqrt(m / a**3)
        ecosE0 = 1.0_wp - r0 / a
        esinE0 = dot_product(q0, v0) / sqrt(m * a)
        E0 = atan2(esinE0, ecosE0)
        M0 = E0 - esinE0
        tred = t - period * real(floor(t / period), wp)       ! same state one period later
        Mt = M0 + nmean * tred
        ! Newton on E - e sin E = Mt, started at a bracket-safe guess
        EE = Mt + 0.85_wp * e * sign(1.0_wp, sin(Mt))
        if (e < 0.8_wp) EE = Mt
        stat = FSYM_ERR_NO_CONVERGENCE
        do it = 1, 100
            dEk = (EE - e * sin(EE) - Mt) / (1.0_wp - e * cos(EE))
            EE = EE - dEk
            if (abs(dEk) <= 16.0_wp * epsilon(1.0_wp) * max(1.0_wp, abs(EE))) then
                stat = FSYM_SUCCESS; exit
            end if
        end do
        if (stat /= FSYM_SUCCESS) return
        dE = EE - E0
        f = 1.0_wp - (a / r0) * (1.0_wp - cos(dE))
        g = tred - (dE - sin(dE)) / nmean
        r = a * (1.0_wp - e * cos(EE))
        fdot = -sqrt(m * a) * sin(dE) / (r * r0)
        gdot = 1.0_wp - (a / r) * (1.0_wp - cos(dE))
        q = f * q0 + g * v0
        v = fdot * q0 + gdot * v0
    end subroutine kepler_exact

    !> The paper's benchmark: q = (10, 0), v = (0, 0.1), mu = 1 (e = 0.9, E0 = -0.095,
    !> period 2000 pi/19^(3/2)).
    pure subroutine kepler_paper_orbit(q, v, period)
        real(wp), intent(out) :: q(2), v(2)       !! initial state
        real(wp), intent(out), optional :: period !! its period
        q = [10.0_wp, 0.0_wp]
        v = [0.0_wp, 0.1_wp]
        if (present(period)) period = 2000.0_wp * FSYM_PI / 19.0_wp**1.5_wp
    end subroutine kepler_paper_orbit

    !> A planar orbit of eccentricity e and semi-major axis 1 (mu = 1) started at pericentre
    !> on the x axis: q = (1-e, 0), v = (0, sqrt((1+e)/(1-e))) (Hairer-Lubich-Wanner).
    !> For e outside [0, 1) there is no such ellipse: `stat` = FSYM_ERR_NOT_ELLIPTIC and
    !> q = v = NaN (so that an integrator refuses the state if `stat` is not looked at).
    pure subroutine kepler_elliptic_orbit(e, q, v, period, stat)
        real(wp), intent(in) :: e                 !! eccentricity, 0 <= e < 1
        real(wp), intent(out) :: q(2), v(2)       !! initial state
        real(wp), intent(out), optional :: period !! its period (2 pi)
        integer, intent(out), optional :: stat    !! FSYM_SUCCESS or FSYM_ERR_NOT_ELLIPTIC
        if (present(stat)) stat = FSYM_SUCCESS
        if (present(period)) period = 2.0_wp * FSYM_PI
        if (.not. (e >= 0.0_wp .and. e < 1.0_wp)) then
            if (present(stat)) stat = FSYM_ERR_NOT_ELLIPTIC
            q = ieee_value(e, ieee_quiet_nan); v = q
            return
        end if
        q = [1.0_wp - e, 0.0_wp]
        v = [0.0_wp, sqrt((1.0_wp + e) / (1.0_wp - e))]
    end subroutine kepler_elliptic_orbit

    pure real(wp) function opt_mu(mu)
        real(wp), intent(in), optional :: mu
        opt_mu = 1.0_wp
        if (present(mu)) opt_mu = mu
    end function opt_mu

    ! ---------------------------------------------------------------- force model bindings

    !> Accelerations of every column of q.
    subroutine kepler_model_acceleration(self, q, a, stat)
        class(kepler_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)               !! accelerations (d, n)
        integer, intent(inout) :: stat                 !! unchanged: never fails itself
        integer :: j0, j1, d, n
        associate (unused => stat); end associate   ! the interface's arguments
        d = size(q, 1); n = size(q, 2)
        ! Threads (when built with OpenMP) over chunks of bodies: the bodies are independent
        ! and every chunk runs the operations of `kepler_field`, so the bits do not depend on
        ! the thread count.
        !$omp parallel do schedule(static) private(j1) if(n >= 2 * OMP_CHUNK)
        do j0 = 1, n, OMP_CHUNK
            j1 = min(n, j0 + OMP_CHUNK - 1)
            call kepler_field(d, j1 - j0 + 1, self%mu, q(:, j0:j1), a(:, j0:j1))
        end do
        !$omp end parallel do
    end subroutine kepler_model_acceleration

    !> Gradient term of every column: -4 mu^2 q/|q|^6.
    subroutine kepler_model_gradient(self, q, a, g, stat)
        class(kepler_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)   !! accelerations at q (g = 4 a/r^3)
        real(wp), intent(out), contiguous :: g(:, :)               !! gradient term (d, n)
        integer, intent(inout) :: stat                 !! unchanged: never fails itself
        integer :: j0, j1, d, n
        associate (unused => stat); end associate   ! the interface's arguments
        d = size(q, 1); n = size(q, 2)
        !$omp parallel do schedule(static) private(j1) if(n >= 2 * OMP_CHUNK)
        do j0 = 1, n, OMP_CHUNK
            j1 = min(n, j0 + OMP_CHUNK - 1)
            call kepler_field_gradient(d, j1 - j0 + 1, self%mu, q(:, j0:j1), a(:, j0:j1), &
                                       g(:, j0:j1))
        end do
        !$omp end parallel do
    end subroutine kepler_model_gradient

    !> Accelerations -mu q_j/|q_j|^3 of n independent bodies on explicit arrays: the one
    !> Kepler force of the library (the model calls it).
    pure subroutine kepler_field(d, n, mu, q, a)
        integer, intent(in) :: d, n               !! dimensions, bodies
        real(wp), intent(in) :: mu                !! G M
        real(wp), intent(in) :: q(d, n)           !! positions
        real(wp), intent(out) :: a(d, n)          !! accelerations
        call scaled_columns(d, n, -mu, q, q, a)
    end subroutine kepler_field

    !> Gradient term g_j = 4 mu a_j/|q_j|^3 (= -4 mu^2 q_j/|q_j|^6) on explicit arrays, given
    !> the accelerations a at q.
    pure subroutine kepler_field_gradient(d, n, mu, q, a, g)
        integer, intent(in) :: d, n               !! dimensions, bodies
        real(wp), intent(in) :: mu                !! G M
        real(wp), intent(in) :: q(d, n)           !! positions
        real(wp), intent(in) :: a(d, n)           !! accelerations at q
        real(wp), intent(out) :: g(d, n)          !! gradient term
        call scaled_columns(d, n, 4.0_wp * mu, q, a, g)
    end subroutine kepler_field_gradient

    !> y_j = (c / |q_j|^3) x_j for every column j. In the plane it works on blocks of
    !> `FIELD_BLOCK` bodies in three passes (|q|^2, the factor, the product), each a simple
    !> loop that vectorises (a single loop was slower there); a few planar bodies, and any
    !> number in space, take one pass (faster there). Every path does the same operations.
    pure subroutine scaled_columns(d, n, c, q, x, y)
        integer, intent(in) :: d, n
        real(wp), intent(in) :: c, q(d, n), x(d, n)
        real(wp), intent(out) :: y(d, n)
        real(wp) :: s(FIELD_BLOCK), r2, f
        integer :: i, j, j0, m
        if (n < FIELD_FUSED_BELOW .and. d == 2) then
            ! a few bodies: one pass (the same operations)
            do j = 1, n
                r2 = q(1, j)**2 + q(2, j)**2
                f = c / (r2 * sqrt(r2))
                y(1, j) = f * x(1, j)
                y(2, j) = f * x(2, j)
            end do
            return
        else if (d == 3) then
            ! in space one pass at any n (measured twice as fast as the passes for n = 1000)
            do j = 1, n
                r2 = q(1, j)**2 + q(2, j)**2 + q(3, j)**2
                f = c / (r2 * sqrt(r2))
                y(1, j) = f * x(1, j)
                y(2, j) = f * x(2, j)
                y(3, j) = f * x(3, j)
            end do
            return
        end if
        do j0 = 0, n - 1, FIELD_BLOCK
            m = min(FIELD_BLOCK, n - j0)
            select case (d)
            case (2)
                do j = 1, m
                    s(j) = q(1, j0 + j)**2 + q(2, j0 + j)**2
                end do
            case default
                do j = 1, m
                    s(j) = sum(q(:, j0 + j)**2)
                end do
            end select
            do j = 1, m
                s(j) = c / (s(j) * sqrt(s(j)))
            end do
            select case (d)
            case (2)
                do j = 1, m
                    y(1, j0 + j) = s(j) * x(1, j0 + j)
                    y(2, j0 + j) = s(j) * x(2, j0 + j)
                end do
            case default
                do j = 1, m
                    do i = 1, d
                        y(i, j0 + j) = s(j) * x(i, j0 + j)
                    end do
                end do
            end select
        end do
    end subroutine scaled_columns

    !> The Kepler model provides the gradient term.
    logical function kepler_model_has_gradient(self)
        class(kepler_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate   ! the interface's arguments
        kepler_model_has_gradient = .true.
    end function kepler_model_has_gradient

    !> Total potential energy of all columns.
    subroutine kepler_model_potential(self, q, epot, stat)
        class(kepler_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                !! positions (d, n)
        real(wp), intent(out) :: epot                  !! sum of -mu/|q_j|
        integer, intent(inout) :: stat                 !! unchanged: never fails itself
        integer :: j
        associate (unused => stat); end associate   ! the interface's arguments
        epot = 0.0_wp
        do j = 1, size(q, 2)
            epot = epot + kepler_potential(q(:, j), self%mu)
        end do
    end subroutine kepler_model_potential

    !> True: the Kepler model provides its potential and the largest local frequency (for the
    !> step-size guard) (`has_potential`, `has_frequency`).
    logical function kepler_model_provides(self)
        class(kepler_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate   ! the interface's arguments
        kepler_model_provides = .true.
    end function kepler_model_provides

    !> Largest local frequency squared, 2 mu / r^3 over the bodies (the oscillation frequency
    !> of a radial perturbation scale at distance r), and the smallest r.
    subroutine kepler_model_frequency(self, q, omega2, r, stat)
        class(kepler_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (d, n)
        real(wp), intent(out) :: omega2               !! largest 2 mu / r^3
        real(wp), intent(out) :: r                    !! smallest distance to the centre
        integer, intent(inout) :: stat                !! unchanged: never fails itself
        integer :: j
        associate (unused => stat); end associate   ! the interface's arguments
        r = huge(r)
        do j = 1, size(q, 2)
            r = min(r, sqrt(sum(q(:, j)**2)))
        end do
        omega2 = 2.0_wp * abs(self%mu) / r**3
    end subroutine kepler_model_frequency

end module fsym_kepler
