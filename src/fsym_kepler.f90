!> Kepler problem in any dimension, H = |v|^2/2 - mu/|q|: acceleration, gradient term,
!> potential, energy, angular momentum, Laplace-Runge-Lenz vector, orbital elements and
!> period, the exact solution at time t (Kepler's equation) and the benchmark orbit of the
!> paper. Scalar physics is pure; `kepler_model_t` is the force model for `n` independent
!> bodies about a fixed centre (columns of q).
module fsym_kepler
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_force, only: force_model_t
    use fsym_kernel_state, only: kernel_state_t, fsym_kernel_invalidate
    use fsym_kernel_loops, only: fsym_loop_entry, fsym_loop_copy
    use fsym_scheme, only: OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK
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
        procedure :: advance => kepler_model_advance  !! one body in d = 2, 3: fused steps
        procedure :: has_advance => kepler_model_provides  !! true
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
        if (.not. (en < 0.0_wp) .or. sum(q**2) == 0.0_wp) then
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

    !> The fused stepper (see `force_model_t%advance`), d = 2 or 3, without compensation.
    !> More than one body: `advance_blocks`. One body runs the scheme's stage table with its
    !> state, forces, cache flags and counters in scalars (the third component is 0 in the
    !> plane, which changes no bit), the force written out with the operations of `kepler_field` and
    !> `kepler_field_gradient`. Bitwise the kernel's steps (`test/test_kernel_fused.pf`).
    !> It stops before the first step whose checks fail: that step is undone on scalars
    !> (the cached forces of its start computed again, uncounted: the same bits) and the
    !> kernel takes it and reports the failure.
    subroutine kepler_model_advance(self, op, c, u, ks, q, v, w, h, nsteps, ndone)
        class(kepler_model_t), intent(inout) :: self              !! the model
        integer, intent(in), contiguous :: op(:)                  !! op codes of the stages
        real(wp), intent(in), contiguous :: c(:), u(:)            !! stage coefficients
        type(kernel_state_t), intent(inout) :: ks                 !! kernel state
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n)   !! state
        real(wp), intent(inout) :: w(ks%d, ks%n, ks%nslot)        !! the kernel's work array
        real(wp), intent(in) :: h                                 !! step
        integer(ik), intent(in) :: nsteps                         !! steps wanted
        integer(ik), intent(out) :: ndone                         !! steps taken
        ! x position, y velocity, a force, g gradient term, e force at the shifted point p
        real(wp) :: x1, x2, x3, y1, y2, y3, a1, a2, a3, g1, g2, g3, e1, e2, e3, p1, p2, p3
        real(wp) :: x01, x02, x03, y01, y02, y03, mu, s, r, xs, xs0, shift
        logical :: ha, hg, hx, ha0, hg0, hx0, ok
        integer(ik) :: i, nf, ng, nf0, ng0
        integer :: k, d
        ndone = 0
        d = ks%d
        if ((d /= 2 .and. d /= 3) .or. ks%comp .or. ks%active) return
        if (ks%n > 1) then
            call advance_blocks(self%mu, op, c, u, ks, q, v, w, h, nsteps, ndone)
            return
        end if
        if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) return
        x3 = 0.0_wp; y3 = 0.0_wp; a1 = 0.0_wp; a2 = 0.0_wp; a3 = 0.0_wp; g1 = 0.0_wp
        g2 = 0.0_wp; g3 = 0.0_wp; e1 = 0.0_wp; e2 = 0.0_wp; e3 = 0.0_wp; p1 = 0.0_wp
        p2 = 0.0_wp; p3 = 0.0_wp
        x1 = q(1, 1); x2 = q(2, 1); y1 = v(1, 1); y2 = v(2, 1)
        if (d == 3) then
            x3 = q(3, 1); y3 = v(3, 1)
        end if
        if (.not. (ieee_is_finite(x1) .and. ieee_is_finite(x2) .and. ieee_is_finite(x3) .and. &
                   ieee_is_finite(y1) .and. ieee_is_finite(y2) .and. ieee_is_finite(y3))) return
        if (ks%have_a) then
            if (any(q(:, 1) /= w(:, 1, ks%iqlast))) then
                call fsym_kernel_invalidate(ks)
            end if
        end if
        mu = self%mu
        ha = ks%have_a; hg = ks%have_g; hx = ks%have_x; xs = ks%xshift
        if (ha) call load(ks%ia, a1, a2, a3)
        if (hg) call load(ks%ig, g1, g2, g3)
        if (hx) then
            call load(ks%iae, e1, e2, e3); call load(ks%iqe, p1, p2, p3)
        end if
        nf = ks%nf; ng = ks%ng
        ok = .true.
        do i = 1, nsteps
            x01 = x1; x02 = x2; x03 = x3; y01 = y1; y02 = y2; y03 = y3
            ha0 = ha; hg0 = hg; hx0 = hx; xs0 = xs; nf0 = nf; ng0 = ng
            do k = 1, size(op)
                if (op(k) /= OP_DRIFT .and. .not. ha) then
                    call field(-mu, x1, x2, x3, x1, x2, x3, a1, a2, a3, ok)
                    if (.not. ok) exit
                    ha = .true.; nf = nf + 1
                end if
                select case (op(k))
                case (OP_DRIFT)
                    s = c(k) * h
                    x1 = x1 + s * y1; x2 = x2 + s * y2; x3 = x3 + s * y3
                    ha = .false.; hg = .false.; hx = .false.
                case (OP_KICK)
                    s = c(k) * h
                    y1 = y1 + s * a1; y2 = y2 + s * a2; y3 = y3 + s * a3
                case (OP_GRAD_KICK)
                    if (.not. hg) then
                        call field(4.0_wp * mu, x1, x2, x3, a1, a2, a3, g1, g2, g3, ok)
                        if (.not. ok) exit
                        hg = .true.; ng = ng + 1
                    end if
                    s = c(k) * h
                    r = u(k) * h**3
                    y1 = y1 + (s * a1 + r * g1); y2 = y2 + (s * a2 + r * g2)
                    y3 = y3 + (s * a3 + r * g3)
                case (OP_EXTRAP_KICK)
                    shift = u(k) * h * h
                    if (.not. hx .or. xs /= shift) then
                        p1 = x1 + shift * a1; p2 = x2 + shift * a2; p3 = x3 + shift * a3
                        xs = shift
                        call field(-mu, p1, p2, p3, p1, p2, p3, e1, e2, e3, ok)
                        if (.not. ok) exit
                        hx = .true.; nf = nf + 1
                    end if
                    s = c(k) * h
                    y1 = y1 + s * e1; y2 = y2 + s * e2; y3 = y3 + s * e3
                case default
                    continue      ! a validated scheme has no other op codes
                end select
            end do
            if (ok) ok = ieee_is_finite(x1) .and. ieee_is_finite(x2) .and. ieee_is_finite(x3) &
                         .and. ieee_is_finite(y1) .and. ieee_is_finite(y2) .and. ieee_is_finite(y3)
            if (.not. ok) then
                ! leave this step to the kernel: back to its start, cache as it was
                x1 = x01; x2 = x02; x3 = x03; y1 = y01; y2 = y02; y3 = y03
                ha = ha0; hg = hg0; hx = hx0; xs = xs0; nf = nf0; ng = ng0
                if (ha) call field(-mu, x1, x2, x3, x1, x2, x3, a1, a2, a3, ok)
                if (hg) call field(4.0_wp * mu, x1, x2, x3, a1, a2, a3, g1, g2, g3, ok)
                if (hx) then
                    p1 = x1 + xs * a1; p2 = x2 + xs * a2; p3 = x3 + xs * a3
                    call field(-mu, p1, p2, p3, p1, p2, p3, e1, e2, e3, ok)
                end if
                exit
            end if
            ndone = i
        end do
        q(1, 1) = x1; q(2, 1) = x2; v(1, 1) = y1; v(2, 1) = y2
        if (d == 3) then
            q(3, 1) = x3; v(3, 1) = y3
        end if
        if (ha) then
            call store(ks%ia, a1, a2, a3); w(:, 1, ks%iqlast) = q(:, 1)
        end if
        if (hg) call store(ks%ig, g1, g2, g3)
        if (hx) then
            call store(ks%iae, e1, e2, e3); call store(ks%iqe, p1, p2, p3)
        end if
        ks%have_a = ha; ks%have_g = hg; ks%have_x = hx; ks%xshift = xs
        ks%nf = nf; ks%ng = ng

    contains

        subroutine load(slot, z1, z2, z3)
            integer, intent(in) :: slot
            real(wp), intent(out) :: z1, z2, z3
            z1 = w(1, 1, slot); z2 = w(2, 1, slot); z3 = 0.0_wp
            if (d == 3) z3 = w(3, 1, slot)
        end subroutine load

        subroutine store(slot, z1, z2, z3)
            integer, intent(in) :: slot
            real(wp), intent(in) :: z1, z2, z3
            w(1, 1, slot) = z1; w(2, 1, slot) = z2
            if (d == 3) w(3, 1, slot) = z3
        end subroutine store

    end subroutine kepler_model_advance

    !> The fused stepper for n > 1 bodies: blocks of `FIELD_BLOCK` bodies, each taking all
    !> the steps in local arrays (the bodies are independent) with the stages as loops over
    !> the block (they vectorise), the force written out with the operations of
    !> `scaled_columns`. All or nothing: when any check fails, q, v and the cache are put
    !> back as they were on entry (the cached forces computed again, uncounted: the same
    !> bits) and no step is taken, so the kernel takes them all and reports the failure.
    !> The checks add z * 0 for every force and state value z to a sum per body (0, or NaN
    !> once any z is not finite): no branch in the vectorised loops, one test per step.
    subroutine advance_blocks(mu, op, c, u, ks, q, v, w, h, nsteps, ndone)
        real(wp), intent(in) :: mu
        integer, intent(in), contiguous :: op(:)
        real(wp), intent(in), contiguous :: c(:), u(:)
        type(kernel_state_t), intent(inout) :: ks
        real(wp), intent(inout) :: q(ks%d, ks%n), v(ks%d, ks%n), w(ks%d, ks%n, ks%nslot)
        real(wp), intent(in) :: h
        integer(ik), intent(in) :: nsteps
        integer(ik), intent(out) :: ndone
        real(wp), dimension(FIELD_BLOCK, 3) :: x, y, a, g, e, p
        real(wp) :: chk(FIELD_BLOCK)   ! z * 0 summed over the checked values z: 0 or NaN
        real(wp) :: s, r, xs, shift
        logical :: ha, hg, hx, ok, okall, differ
        integer(ik) :: i, nf, ng
        integer :: d, n, j0, m, k, l
        d = ks%d; n = ks%n
        ndone = 0
        if (nsteps < 1) return
        if (.not. (h /= 0.0_wp .and. abs(h) <= huge(h))) return
        ! the entry state checked, and q compared with the cached force's point, in one loop;
        ! each block saves its entry state as it loads it (below)
        if (.not. fsym_loop_entry(d * n, q, v, w(:, :, ks%iqlast), ks%have_a, differ)) return
        if (differ) call fsym_kernel_invalidate(ks)
        okall = .true.
        x = 0.0_wp; y = 0.0_wp; a = 0.0_wp; g = 0.0_wp; e = 0.0_wp; p = 0.0_wp
        ha = ks%have_a; hg = ks%have_g; hx = ks%have_x; xs = ks%xshift
        nf = ks%nf; ng = ks%ng
        ! Threads (when built with OpenMP) over the blocks: each block takes all the steps on
        ! its own bodies, so the bits do not depend on the thread count; every block ends with
        ! the same cache flags and counts (the same stages, the same steps), taken from the
        ! last one. A failing block is not written back; then all are undone below.
        !$omp parallel do schedule(static) default(shared) reduction(.and.:okall) &
        !$omp firstprivate(x, y, a, g, e, p) private(m, l, i, k, s, r, shift, ok, chk) &
        !$omp lastprivate(ha, hg, hx, xs, nf, ng) if(n >= 4 * FIELD_BLOCK)
        do j0 = 0, n - 1, FIELD_BLOCK
            m = min(FIELD_BLOCK, n - j0)
            ok = .true.
            chk = 0.0_wp
            ha = ks%have_a; hg = ks%have_g; hx = ks%have_x; xs = ks%xshift
            nf = ks%nf; ng = ks%ng
            call to_block(d, m, q(:, j0 + 1:j0 + m), x); call to_block(d, m, v(:, j0 + 1:j0 + m), y)
            ! the entry state saved while in cache
            call fsym_loop_copy(d * m, q(:, j0 + 1:j0 + m), w(:, j0 + 1:j0 + m, ks%iq0))
            call fsym_loop_copy(d * m, v(:, j0 + 1:j0 + m), w(:, j0 + 1:j0 + m, ks%iv0))
            if (ha) call to_block(d, m, w(:, j0 + 1:j0 + m, ks%ia), a)
            if (hg) call to_block(d, m, w(:, j0 + 1:j0 + m, ks%ig), g)
            if (hx) call to_block(d, m, w(:, j0 + 1:j0 + m, ks%iae), e)
            if (hx) call to_block(d, m, w(:, j0 + 1:j0 + m, ks%iqe), p)
            steps: do i = 1, nsteps
                do k = 1, size(op)
                    if (op(k) /= OP_DRIFT .and. .not. ha) then
                        call block_field(-mu, m, d, x, x, a, chk)
                        ha = .true.; nf = nf + 1
                    end if
                    select case (op(k))
                    case (OP_DRIFT)
                        s = c(k) * h
                        x(1:m, 1:d) = x(1:m, 1:d) + s * y(1:m, 1:d)
                        ha = .false.; hg = .false.; hx = .false.
                    case (OP_KICK)
                        s = c(k) * h
                        y(1:m, 1:d) = y(1:m, 1:d) + s * a(1:m, 1:d)
                    case (OP_GRAD_KICK)
                        if (.not. hg) then
                            call block_field(4.0_wp * mu, m, d, x, a, g, chk)
                            hg = .true.; ng = ng + 1
                        end if
                        s = c(k) * h
                        r = u(k) * h**3
                        y(1:m, 1:d) = y(1:m, 1:d) + (s * a(1:m, 1:d) + r * g(1:m, 1:d))
                    case (OP_EXTRAP_KICK)
                        shift = u(k) * h * h
                        if (.not. hx .or. xs /= shift) then
                            p(1:m, 1:d) = x(1:m, 1:d) + shift * a(1:m, 1:d)
                            xs = shift
                            call block_field(-mu, m, d, p, p, e, chk)
                            hx = .true.; nf = nf + 1
                        end if
                        s = c(k) * h
                        y(1:m, 1:d) = y(1:m, 1:d) + s * e(1:m, 1:d)
                    case default
                        continue      ! a validated scheme has no other op codes
                    end select
                end do
                do l = 1, d
                    chk(1:m) = chk(1:m) + (x(1:m, l) * 0.0_wp + y(1:m, l) * 0.0_wp)
                end do
                ok = all(chk(1:m) == 0.0_wp)
                if (.not. ok) exit steps
            end do steps
            okall = okall .and. ok
            if (.not. ok) cycle
            call from_block(d, m, x, q(:, j0 + 1:j0 + m))
            if (ha) call fsym_loop_copy(d * m, q(:, j0 + 1:j0 + m), &
                                        w(:, j0 + 1:j0 + m, ks%iqlast))
            call from_block(d, m, y, v(:, j0 + 1:j0 + m))
            if (ha) call from_block(d, m, a, w(:, j0 + 1:j0 + m, ks%ia))
            if (hg) call from_block(d, m, g, w(:, j0 + 1:j0 + m, ks%ig))
            if (hx) call from_block(d, m, e, w(:, j0 + 1:j0 + m, ks%iae))
            if (hx) call from_block(d, m, p, w(:, j0 + 1:j0 + m, ks%iqe))
        end do
        !$omp end parallel do
        if (.not. okall) then
            ! all or nothing: the entry state and its cache (same bits), nothing counted
            q = w(:, :, ks%iq0); v = w(:, :, ks%iv0)
            if (ks%have_a) w(:, :, ks%iqlast) = q     ! the point of the cache, as on entry
            if (ks%have_a) call scaled_columns(d, n, -mu, q, q, w(:, :, ks%ia))
            if (ks%have_g) call scaled_columns(d, n, 4.0_wp * mu, q, w(:, :, ks%ia), &
                                               w(:, :, ks%ig))
            if (ks%have_x) then
                w(:, :, ks%iqe) = q + ks%xshift * w(:, :, ks%ia)
                call scaled_columns(d, n, -mu, w(:, :, ks%iqe), w(:, :, ks%iqe), w(:, :, ks%iae))
            end if
            return
        end if
        ks%have_a = ha; ks%have_g = hg; ks%have_x = hx; ks%xshift = xs
        ks%nf = nf; ks%ng = ng
        ndone = nsteps
    end subroutine advance_blocks

    !> b(j, l) = z(l, j): m bodies (columns) into a block (rows), d = 2 or 3 written out.
    pure subroutine to_block(d, m, z, b)
        integer, intent(in) :: d, m
        real(wp), intent(in) :: z(d, m)
        real(wp), intent(inout) :: b(FIELD_BLOCK, 3)
        integer :: j
        if (d == 2) then
            do j = 1, m
                b(j, 1) = z(1, j); b(j, 2) = z(2, j)
            end do
        else
            do j = 1, m
                b(j, 1) = z(1, j); b(j, 2) = z(2, j); b(j, 3) = z(3, j)
            end do
        end if
    end subroutine to_block

    !> z(l, j) = b(j, l): a block back into m columns, d = 2 or 3 written out.
    pure subroutine from_block(d, m, b, z)
        integer, intent(in) :: d, m
        real(wp), intent(in) :: b(FIELD_BLOCK, 3)
        real(wp), intent(inout) :: z(d, m)
        integer :: j
        if (d == 2) then
            do j = 1, m
                z(1, j) = b(j, 1); z(2, j) = b(j, 2)
            end do
        else
            do j = 1, m
                z(1, j) = b(j, 1); z(2, j) = b(j, 2); z(3, j) = b(j, 3)
            end do
        end if
    end subroutine from_block

    !> f = (cf / |r|^3) z for the m bodies of a block (the operations of `scaled_columns`);
    !> f * 0 added to `chk` (it becomes NaN where any f is not finite; no branch, vectorised).
    pure subroutine block_field(cf, m, d, r, z, f, chk)
        real(wp), intent(in) :: cf
        integer, intent(in) :: m, d
        real(wp), intent(in) :: r(FIELD_BLOCK, 3), z(FIELD_BLOCK, 3)
        real(wp), intent(inout) :: f(FIELD_BLOCK, 3)
        real(wp), intent(inout) :: chk(FIELD_BLOCK)
        real(wp) :: t
        integer :: j
        if (d == 2) then
            do j = 1, m
                t = r(j, 1)**2 + r(j, 2)**2
                t = cf / (t * sqrt(t))
                f(j, 1) = t * z(j, 1); f(j, 2) = t * z(j, 2)
                chk(j) = chk(j) + (f(j, 1) * 0.0_wp + f(j, 2) * 0.0_wp)
            end do
        else
            do j = 1, m
                t = r(j, 1)**2 + r(j, 2)**2 + r(j, 3)**2
                t = cf / (t * sqrt(t))
                f(j, 1) = t * z(j, 1); f(j, 2) = t * z(j, 2); f(j, 3) = t * z(j, 3)
                chk(j) = chk(j) + (f(j, 1) * 0.0_wp + f(j, 2) * 0.0_wp + f(j, 3) * 0.0_wp)
            end do
        end if
    end subroutine block_field

    !> f = (cf / |r|^3) z with |r|^2 = r1^2 + r2^2 + r3^2 (the operations of
    !> `scaled_columns`); `ok` false when f is not finite.
    pure subroutine field(cf, r1, r2, r3, z1, z2, z3, f1, f2, f3, ok)
        real(wp), intent(in) :: cf, r1, r2, r3, z1, z2, z3
        real(wp), intent(out) :: f1, f2, f3
        logical, intent(out) :: ok
        real(wp) :: rr, t
        rr = r1**2 + r2**2 + r3**2
        t = cf / (rr * sqrt(rr))
        f1 = t * z1; f2 = t * z2; f3 = t * z3
        ok = ieee_is_finite(f1) .and. ieee_is_finite(f2) .and. ieee_is_finite(f3)
    end subroutine field

    !> The Kepler model provides the gradient term.
    logical function kepler_model_has_gradient(self)
        class(kepler_model_t), intent(in) :: self  !! the model
        kepler_model_has_gradient = .true.
    end function kepler_model_has_gradient

    !> Total potential energy of all columns.
    subroutine kepler_model_potential(self, q, epot, stat)
        class(kepler_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                !! positions (d, n)
        real(wp), intent(out) :: epot                  !! sum of -mu/|q_j|
        integer, intent(inout) :: stat                 !! unchanged: never fails itself
        integer :: j
        epot = 0.0_wp
        do j = 1, size(q, 2)
            epot = epot + kepler_potential(q(:, j), self%mu)
        end do
    end subroutine kepler_model_potential

    !> True: the Kepler model provides its potential, the largest local frequency (for the
    !> step-size guard) and a fused stepper (`has_potential`, `has_frequency`, `has_advance`).
    logical function kepler_model_provides(self)
        class(kepler_model_t), intent(in) :: self  !! the model
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
        r = huge(r)
        do j = 1, size(q, 2)
            r = min(r, sqrt(sum(q(:, j)**2)))
        end do
        omega2 = 2.0_wp * abs(self%mu) / r**3
    end subroutine kepler_model_frequency

end module fsym_kepler
