!> Planetary systems: the Wisdom-Holman splitting H = H_Kepler + H_interaction as a force
!> model, so that every stage table of the catalogue runs with Kepler drifts (T2 with Kepler
!> drifts is the plain Wisdom-Holman map). A central body of mass m0 and n bodies, the first
!> `nm` massive and the rest test particles (mass 0: they feel the centre and the massive
!> bodies and act on nothing; their cost is n_test x (nm + 1) pairs). G and the masses are
!> the user's (see doc/planets.md for Mercury's k^2 and SWIFT's units).
!>
!> State arrays q(3, n), v(3, n) hold, per coordinate set:
!>
!> * `PLANETS_JACOBI`: Jacobi positions q'_k = x_k - X_{k-1} (X_k the centre of mass of the
!>   centre and bodies 1..k, eta_k their mass) and velocities v'_k. H_Kepler = sum_k
!>   [m'_k |v'_k|^2/2 - G m'_k M_k / |q'_k|] with kinetic masses m'_k = m_k eta_{k-1}/eta_k
!>   and M_k = m0 eta_k/eta_{k-1} (J. Wisdom and M. Holman, AJ 102 (1991) 1528), or with
!>   `kepler_masses = PLANETS_KEPLER_ETA` M_k = eta_k (the interior mass including body k,
!>   REBOUND's WHFast choice; measured on the outer solar system with correctors: 1.3x
!>   smaller energy errors, doc/planets.md); H_interaction = V(x) + sum_k G m'_k M_k /
!>   |q'_k| (V the full Newtonian potential) depends on positions only, so there is no
!>   other term, for either choice.
!> * `PLANETS_DEMOCRATIC`: heliocentric positions Q_i = x_i - x_0 and barycentric velocities
!>   (Duncan, Levison & Lee 1998). H_Kepler = sum_i [m_i |V_i|^2/2 - G m0 m_i/|Q_i|],
!>   H_interaction = -sum_{i<j} G m_i m_j/|Q_i - Q_j|, and the jump term H_jump = |sum_i m_i
!>   V_i|^2/(2 m0), which depends on velocities only. The drift is folded as
!>   jump(dt/2) o Kepler(dt) o jump(dt/2): exact to second order in its own splitting.
!>   As H_jump is of the interaction's relative size eps, that leaves an error eps h^2 in
!>   every table: measured, all the 4th-order tables fall to p = q = 2 in democratic
!>   coordinates (doc/planets.md). Jacobi coordinates have no such term: use them for the
!>   high-order tables.
!>
!> The kick is the interaction acceleration (in the state's coordinates; in Jacobi
!> coordinates the inertial accelerations carried over by the Jacobi map, minus the Kepler
!> part), plus an optional user force model `extra` acting on the heliocentric positions (a
!> J2, a post-Newtonian term, a disk). The gradient term (library convention g_j = (1/m'_j)
!> d/dq_j sum_i m'_i |a_i|^2 with the kinetic masses) is, because m'_i a_i = -dH_int/dq_i
!> makes the Jacobian m-symmetric, g = 2 (Da) a: twice the derivative of the interaction
!> acceleration along itself, computed exactly over the same pairs as the force (and for
!> test particles the limit m -> 0 of the same formula). As [H_int, H_Kepler - T] = 0, this
!> is the paper's [V, [T, V]] term for the interaction: the forward kernels carry over. With
!> an `extra` model the gradient is not offered; the extrapolated kicks (A', C', ...) work.
!>
!> Close encounters: with `hill` > 0, a kick refuses a state where two bodies (a massive pair
!> or a test particle and a massive body) are closer than `hill` mutual Hill radii
!> ((m_i + m_j)/(3 m0))^(1/3) (|Q_i| + |Q_j|)/2: it returns PLANETS_ENCOUNTER, the kernel
!> undoes the step (state as it was), and `encounter_i`, `encounter_j` and `message` name
!> the pair, so the host can hand over. Every face then reports the library status
!> FSYM_ERR_ENCOUNTER with that message (`failure`, called by the faces after a failed step).
module fsym_planets
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use fsym_kinds, only: wp, ik, fsym_same
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_ARGUMENT, FSYM_ERR_SHAPE, fsym_report, &
                           fsym_int_text, FSYM_ERR_ENCOUNTER, FSYM_ERR_NOT_INITIALIZED
    use fsym_force, only: force_model_t
    use fsym_kepler_universal, only: fsym_kepler_drift_many
    implicit none
    private

    integer, parameter, public :: PLANETS_JACOBI = 1      !! Jacobi coordinates
    integer, parameter, public :: PLANETS_DEMOCRATIC = 2  !! democratic heliocentric
    !> Model status of a kick that found a close encounter (the kernel reports it as the
    !> model's failure and undoes the step; the model keeps the pair).
    integer, parameter, public :: PLANETS_ENCOUNTER = 1001
    !> Model status of a drift whose Kepler solve failed (the model keeps the body).
    integer, parameter, public :: PLANETS_KEPLER_FAILED = 1002
    !> Model status of a call on a model that was never set up (`init` not called or failed).
    integer, parameter, public :: PLANETS_NOT_SET_UP = 1003
    !> Jacobi Kepler masses M_k = m0 eta_k/eta_{k-1} (Wisdom & Holman 1991; the default).
    integer, parameter, public :: PLANETS_KEPLER_WH = 1
    !> Jacobi Kepler masses M_k = eta_k (as REBOUND's WHFast).
    integer, parameter, public :: PLANETS_KEPLER_ETA = 2

    !> A central body and n bodies (nm massive, then n - nm test particles) under the
    !> Wisdom-Holman splitting.
    type, extends(force_model_t), public :: planets_model_t
        integer :: coords = PLANETS_JACOBI   !! PLANETS_JACOBI or PLANETS_DEMOCRATIC
        integer :: n = 0                     !! bodies besides the centre
        integer :: nm = 0                    !! massive bodies (the first nm)
        real(wp) :: g = 1.0_wp               !! gravitational constant
        real(wp) :: m0 = 1.0_wp              !! central mass
        real(wp) :: hill = 0.0_wp            !! encounter radius in mutual Hill radii (0: off)
        real(wp), allocatable :: m(:)        !! masses (0:n), m(0) = m0
        real(wp), allocatable :: eta(:)      !! interior masses eta_k = m0 + ... + m_k (0:n)
        real(wp), allocatable :: mkin(:)     !! kinetic masses (n) of the coordinate set
        real(wp), allocatable :: gmk(:)      !! gm of each body's Kepler flow (n)
        !> optional extra force on the heliocentric positions (no gradient term then)
        class(force_model_t), allocatable :: extra
        integer :: encounter_i = 0           !! pair of the last encounter (0 0: none)
        integer :: encounter_j = 0           !! second body of that pair
        integer :: kepler_body = 0           !! body of the last failed Kepler solve
        !> why the last call of `acceleration` or `drift` failed (PLANETS_ENCOUNTER,
        !> PLANETS_KEPLER_FAILED; 0: it did not, or the `extra` model failed)
        integer :: failed = 0
        character(len=160) :: message = ''   !! text of the last encounter or failure
        integer(ik) :: ndrift = 0            !! Kepler drifts taken (calls of `drift`)
        real(wp), allocatable, private :: x(:, :), ax(:, :), dx(:, :), dax(:, :)  ! (3, 0:n)
        real(wp), allocatable, private :: qh(:, :), ah(:, :)                      ! (3, n)
        real(wp), allocatable, private :: rh(:)                                   ! (n)
    contains
        procedure :: init => planets_init                 !! set masses, G, coordinates
        procedure :: acceleration => planets_acceleration !! interaction (+ extra) kick
        procedure :: gradient => planets_gradient         !! 2 (Da) a of the interaction
        procedure :: has_gradient => planets_has_gradient !! true unless `extra` is set
        procedure :: drift => planets_drift               !! Kepler flow of every body
        procedure :: has_drift => planets_has_drift       !! true
        procedure :: energy => planets_energy             !! total energy of a state
        procedure :: to_state => planets_to_state         !! barycentric -> state arrays
        procedure :: from_state => planets_from_state     !! state arrays -> barycentric
        procedure :: failure => planets_failure           !! encounter -> FSYM_ERR_ENCOUNTER
    end type planets_model_t

    public :: planets_helio_to_bary, planets_bary_to_helio
    public :: planets_bary_to_jacobi, planets_jacobi_to_bary

contains

    !> Set the system: central mass, masses of the n bodies (the first nm > 0, the rest 0:
    !> test particles), G, coordinates and the encounter radius.
    subroutine planets_init(self, m0, m, g, coords, stat, errmsg, hill, kepler_masses)
        class(planets_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in) :: m0                      !! central mass (> 0)
        real(wp), intent(in) :: m(:)                    !! masses of the bodies (>= 0)
        real(wp), intent(in) :: g                       !! gravitational constant (> 0)
        integer, intent(in) :: coords                   !! PLANETS_JACOBI or _DEMOCRATIC
        integer, intent(out), optional :: stat          !! status
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp), intent(in), optional :: hill          !! encounter radius (Hill radii)
        integer, intent(in), optional :: kepler_masses
            !! Jacobi only: PLANETS_KEPLER_WH (default) or PLANETS_KEPLER_ETA
        integer :: n, k, km
        n = size(m)
        if (.not. (m0 > 0.0_wp .and. g > 0.0_wp .and. m0 <= huge(m0) .and. g <= huge(g)) &
            .or. .not. all(m >= 0.0_wp .and. m <= huge(m0)) .or. n < 1) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'planets: need m0 > 0, G > 0, n >= 1 '// &
                             'and finite masses >= 0', stat, errmsg)
            return
        end if
        if (coords /= PLANETS_JACOBI .and. coords /= PLANETS_DEMOCRATIC) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'planets: unknown coordinate set', &
                             stat, errmsg)
            return
        end if
        km = PLANETS_KEPLER_WH
        if (present(kepler_masses)) km = kepler_masses
        if (km /= PLANETS_KEPLER_WH .and. km /= PLANETS_KEPLER_ETA) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'planets: unknown Kepler mass choice', &
                             stat, errmsg)
            return
        end if
        self%nm = count(m > 0.0_wp)
        if (any(fsym_same(m(1:self%nm), 0.0_wp))) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'planets: massive bodies first, then '// &
                             'the test particles (mass 0)', stat, errmsg)
            return
        end if
        self%n = n
        self%m0 = m0
        self%g = g
        self%coords = coords
        self%hill = 0.0_wp
        if (present(hill)) self%hill = max(hill, 0.0_wp)
        if (allocated(self%m)) deallocate (self%m, self%eta, self%mkin, self%gmk, self%x, &
                                           self%ax, self%dx, self%dax, self%qh, self%ah, self%rh)
        allocate (self%m(0:n), self%eta(0:n), self%mkin(n), self%gmk(n), self%x(3, 0:n), &
                  self%ax(3, 0:n), self%dx(3, 0:n), self%dax(3, 0:n), self%qh(3, n), &
                  self%ah(3, n), self%rh(n))
        self%m(0) = m0
        self%m(1:n) = m
        self%eta(0) = m0
        do k = 1, n
            self%eta(k) = self%eta(k - 1) + m(k)
        end do
        if (coords == PLANETS_JACOBI) then
            do k = 1, n
                self%mkin(k) = m(k) * self%eta(k - 1) / self%eta(k)
                if (km == PLANETS_KEPLER_ETA) then
                    self%gmk(k) = g * self%eta(k)
                else
                    self%gmk(k) = g * m0 * self%eta(k) / self%eta(k - 1)
                end if
            end do
        else
            self%mkin = m
            self%gmk = g * m0
        end if
        self%encounter_i = 0; self%encounter_j = 0; self%kepler_body = 0
        self%message = ''
        self%ndrift = 0
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine planets_init

    ! ---- coordinates -------------------------------------------------------------------

    !> Heliocentric (relative to the centre) to barycentric positions and velocities.
    pure subroutine planets_helio_to_bary(n, m, xh, vh, xb, vb)
        integer, intent(in) :: n                   !! bodies besides the centre
        real(wp), intent(in) :: m(0:n)             !! masses, m(0) the centre's
        real(wp), intent(in) :: xh(3, n), vh(3, n) !! heliocentric state of the bodies
        real(wp), intent(out) :: xb(3, 0:n)        !! barycentric positions (centre: 0)
        real(wp), intent(out) :: vb(3, 0:n)        !! barycentric velocities
        integer :: i
        xb(:, 0) = 0.0_wp
        vb(:, 0) = 0.0_wp
        do i = 1, n
            xb(:, 0) = xb(:, 0) - m(i) * xh(:, i)
            vb(:, 0) = vb(:, 0) - m(i) * vh(:, i)
        end do
        xb(:, 0) = xb(:, 0) / sum(m)
        vb(:, 0) = vb(:, 0) / sum(m)
        do i = 1, n
            xb(:, i) = xh(:, i) + xb(:, 0)
            vb(:, i) = vh(:, i) + vb(:, 0)
        end do
    end subroutine planets_helio_to_bary

    !> Inertial to heliocentric positions and velocities.
    pure subroutine planets_bary_to_helio(n, xb, vb, xh, vh)
        integer, intent(in) :: n                     !! bodies besides the centre
        real(wp), intent(in) :: xb(3, 0:n), vb(3, 0:n)  !! inertial state (centre: column 0)
        real(wp), intent(out) :: xh(3, n), vh(3, n)  !! heliocentric state
        integer :: i
        do i = 1, n
            xh(:, i) = xb(:, i) - xb(:, 0)
            vh(:, i) = vb(:, i) - vb(:, 0)
        end do
    end subroutine planets_bary_to_helio

    !> Inertial positions (or velocities, or accelerations) to Jacobi ones and the centre of
    !> mass: q_k = x_k - X_{k-1}, X_k = (eta_{k-1} X_{k-1} + m_k x_k)/eta_k.
    pure subroutine planets_bary_to_jacobi(n, m, eta, x, q, xcm)
        integer, intent(in) :: n               !! bodies besides the centre
        real(wp), intent(in) :: m(0:n)         !! masses
        real(wp), intent(in) :: eta(0:n)       !! interior masses m0 + ... + m_k
        real(wp), intent(in) :: x(3, 0:n)      !! inertial vectors
        real(wp), intent(out) :: q(3, n)       !! Jacobi vectors
        real(wp), intent(out) :: xcm(3)        !! centre of mass (or its velocity)
        integer :: k
        xcm = x(:, 0)
        do k = 1, n
            q(:, k) = x(:, k) - xcm
            xcm = xcm + (m(k) / eta(k)) * q(:, k)
        end do
    end subroutine planets_bary_to_jacobi

    !> Jacobi vectors and the centre of mass to inertial ones (the inverse map).
    pure subroutine planets_jacobi_to_bary(n, m, eta, q, xcm, x)
        integer, intent(in) :: n               !! bodies besides the centre
        real(wp), intent(in) :: m(0:n)         !! masses
        real(wp), intent(in) :: eta(0:n)       !! interior masses
        real(wp), intent(in) :: q(3, n)        !! Jacobi vectors
        real(wp), intent(in) :: xcm(3)         !! centre of mass (or its velocity)
        real(wp), intent(out) :: x(3, 0:n)     !! inertial vectors
        real(wp) :: s(3)
        integer :: k
        s = xcm
        do k = n, 1, -1
            s = s - (m(k) / eta(k)) * q(:, k)
            x(:, k) = s + q(:, k)
        end do
        x(:, 0) = s
    end subroutine planets_jacobi_to_bary

    !> The state arrays of the model's coordinate set from an inertial state (any frame; the
    !> centre of mass is returned so that `from_state` can restore the frame).
    subroutine planets_to_state(self, xb, vb, q, v, xcm, vcm, stat, errmsg)
        class(planets_model_t), intent(in) :: self     !! the model (after init)
        real(wp), intent(in) :: xb(3, 0:self%n)        !! inertial positions (centre: 0)
        real(wp), intent(in) :: vb(3, 0:self%n)        !! inertial velocities
        real(wp), intent(out) :: q(3, self%n)          !! state positions
        real(wp), intent(out) :: v(3, self%n)          !! state velocities
        real(wp), intent(out) :: xcm(3), vcm(3)        !! centre of mass and its velocity
        integer, intent(out), optional :: stat         !! status (absent: stop on error)
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: i
        if (present(stat)) stat = FSYM_SUCCESS
        if (.not. allocated(self%m)) then    ! never set up: nothing to convert
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'planets: to_state on a model that '// &
                             'was never set up (call init first)', stat, errmsg)
            return
        end if
        if (self%coords == PLANETS_JACOBI) then
            call planets_bary_to_jacobi(self%n, self%m, self%eta, xb, q, xcm)
            call planets_bary_to_jacobi(self%n, self%m, self%eta, vb, v, vcm)
        else
            xcm = 0.0_wp
            vcm = 0.0_wp
            do i = 0, self%n
                xcm = xcm + (self%m(i) / self%eta(self%n)) * xb(:, i)
                vcm = vcm + (self%m(i) / self%eta(self%n)) * vb(:, i)
            end do
            do i = 1, self%n
                q(:, i) = xb(:, i) - xb(:, 0)
                v(:, i) = vb(:, i) - vcm
            end do
        end if
    end subroutine planets_to_state

    !> The inertial state from the state arrays and the centre of mass (`to_state`'s inverse).
    subroutine planets_from_state(self, q, v, xcm, vcm, xb, vb, stat, errmsg)
        class(planets_model_t), intent(in) :: self     !! the model (after init)
        real(wp), intent(in) :: q(3, self%n), v(3, self%n)  !! state arrays
        real(wp), intent(in) :: xcm(3), vcm(3)         !! centre of mass and its velocity
        real(wp), intent(out) :: xb(3, 0:self%n)       !! inertial positions
        real(wp), intent(out) :: vb(3, 0:self%n)       !! inertial velocities
        integer, intent(out), optional :: stat         !! status (absent: stop on error)
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp) :: mt
        integer :: i
        if (present(stat)) stat = FSYM_SUCCESS
        if (.not. allocated(self%m)) then    ! never set up: nothing to convert
            call fsym_report(FSYM_ERR_NOT_INITIALIZED, 'planets: from_state on a model that '// &
                             'was never set up (call init first)', stat, errmsg)
            return
        end if
        if (self%coords == PLANETS_JACOBI) then
            call planets_jacobi_to_bary(self%n, self%m, self%eta, q, xcm, xb)
            call planets_jacobi_to_bary(self%n, self%m, self%eta, v, vcm, vb)
        else
            mt = self%eta(self%n)
            xb(:, 0) = xcm
            vb(:, 0) = 0.0_wp
            do i = 1, self%n
                xb(:, 0) = xb(:, 0) - (self%m(i) / mt) * q(:, i)
                vb(:, 0) = vb(:, 0) - (self%m(i) / self%m0) * v(:, i)
            end do
            do i = 1, self%n
                xb(:, i) = q(:, i) + xb(:, 0)
                vb(:, i) = v(:, i) + vcm
            end do
            vb(:, 0) = vb(:, 0) + vcm
        end if
    end subroutine planets_from_state

    !> Total energy (kinetic + Newtonian potential, in the centre-of-mass frame) of a state;
    !> NaN for a model that was never set up.
    real(wp) function planets_energy(self, q, v) result(e)
        class(planets_model_t), intent(inout) :: self  !! the model (after init)
        real(wp), intent(in) :: q(3, self%n), v(3, self%n)  !! state arrays
        real(wp) :: z(3)
        integer :: i, j
        if (.not. allocated(self%m)) then    ! never set up: NaN (documented), never a stop
            e = ieee_value(e, ieee_quiet_nan)
            return
        end if
        z = 0.0_wp
        call self%from_state(q, v, z, z, self%x, self%dx)
        e = 0.0_wp
        do i = 0, self%nm
            e = e + 0.5_wp * self%m(i) * sum(self%dx(:, i)**2)
        end do
        do i = 0, self%nm
            do j = i + 1, self%nm
                e = e - self%g * self%m(i) * self%m(j) / norm2(self%x(:, j) - self%x(:, i))
            end do
        end do
    end function planets_energy

    ! ---- the splitting -----------------------------------------------------------------

    !> The Kepler flow of every body over dt (for democratic coordinates wrapped in two
    !> half jumps). On a failed solve: stat = PLANETS_KEPLER_FAILED (the kernel restores).
    subroutine planets_drift(self, q, v, dt, stat)
        class(planets_model_t), intent(inout) :: self   !! the model
        real(wp), intent(inout), contiguous :: q(:, :)  !! positions (3, n)
        real(wp), intent(inout), contiguous :: v(:, :)  !! velocities (3, n)
        real(wp), intent(in) :: dt                      !! time to flow
        integer, intent(inout) :: stat                  !! 0 on entry; non-zero = failure
        integer :: st, ifail
        if (not_set_up(self, stat)) return
        self%ndrift = self%ndrift + 1
        self%failed = 0
        if (self%coords == PLANETS_DEMOCRATIC) call jump(0.5_wp * dt)
        call fsym_kepler_drift_many(self%n, self%gmk, q, v, dt, st, ifail)
        if (st /= FSYM_SUCCESS) then
            self%kepler_body = ifail
            self%message = 'planets: the Kepler solve of body '//fsym_int_text(ifail)// &
                           ' failed (state not finite, or no convergence)'
            stat = PLANETS_KEPLER_FAILED
            self%failed = stat
            return
        end if
        if (self%coords == PLANETS_DEMOCRATIC) call jump(0.5_wp * dt)
    contains
        !> The flow of H_jump: every heliocentric position moves by t P_total / m0.
        subroutine jump(t)
            real(wp), intent(in) :: t
            real(wp) :: p(3)
            integer :: i
            p = 0.0_wp
            do i = 1, self%nm
                p = p + self%m(i) * v(:, i)
            end do
            p = (t / self%m0) * p
            do i = 1, self%n
                q(:, i) = q(:, i) + p
            end do
        end subroutine jump
    end subroutine planets_drift

    !> Whether `drift` is overridden: yes.
    logical function planets_has_drift(self)
        class(planets_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate   ! the interface's arguments
        planets_has_drift = .true.
    end function planets_has_drift

    !> The gradient term is offered unless an extra force model is set.
    logical function planets_has_gradient(self)
        class(planets_model_t), intent(in) :: self  !! the model
        planets_has_gradient = .not. allocated(self%extra)
    end function planets_has_gradient

    !> The interaction acceleration in the state's coordinates (plus `extra`); with `hill` >
    !> 0 a close pair fails the kick with PLANETS_ENCOUNTER.
    subroutine planets_acceleration(self, q, a, stat)
        class(planets_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (3, n)
        real(wp), intent(out), contiguous :: a(:, :)    !! accelerations (3, n)
        integer, intent(inout) :: stat                  !! 0 on entry; non-zero = failure
        real(wp) :: z(3), r2
        integer :: i0, k
        if (not_set_up(self, stat)) return
        self%failed = 0
        z = 0.0_wp
        if (self%coords == PLANETS_JACOBI) then
            call planets_jacobi_to_bary(self%n, self%m, self%eta, q, z, self%x)
            i0 = 0
        else
            self%x(:, 0) = 0.0_wp
            self%x(:, 1:self%n) = q
            i0 = 1
        end if
        if (self%hill > 0.0_wp) then
            call check_encounters(self, stat)
            if (stat /= 0) then
                a = 0.0_wp
                return
            end if
        end if
        call pair_field(self%n, self%nm, i0, self%g, self%m, self%x, self%ax)
        if (allocated(self%extra)) then
            do k = 1, self%n
                self%qh(:, k) = self%x(:, k) - self%x(:, 0)
            end do
            call self%extra%acceleration(self%qh, self%ah, stat)
            if (stat /= 0) return
            self%ax(:, 1:self%n) = self%ax(:, 1:self%n) + self%ah
        end if
        if (self%coords == PLANETS_JACOBI) then
            call planets_bary_to_jacobi(self%n, self%m, self%eta, self%ax, a, z)
            do k = 1, self%n
                r2 = q(1, k)**2 + q(2, k)**2 + q(3, k)**2
                a(:, k) = a(:, k) + (self%gmk(k) / (r2 * sqrt(r2))) * q(:, k)
            end do
        else
            a = self%ax(:, 1:self%n)
        end if
    end subroutine planets_acceleration

    !> The gradient term g = 2 (Da) a of the interaction acceleration a (given).
    subroutine planets_gradient(self, q, a, g, stat)
        class(planets_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (3, n)
        real(wp), intent(in), contiguous :: a(:, :)     !! interaction accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)    !! gradient term (3, n)
        integer, intent(inout) :: stat                  !! 0 on entry; non-zero = failure
        real(wp) :: z(3), r2, qa
        integer :: i0, k
        if (not_set_up(self, stat)) return
        if (allocated(self%extra)) then
            g = 0.0_wp
            stat = 1
            return
        end if
        z = 0.0_wp
        if (self%coords == PLANETS_JACOBI) then
            call planets_jacobi_to_bary(self%n, self%m, self%eta, q, z, self%x)
            call planets_jacobi_to_bary(self%n, self%m, self%eta, a, z, self%dx)
            i0 = 0
        else
            self%x(:, 0) = 0.0_wp
            self%x(:, 1:self%n) = q
            self%dx(:, 0) = 0.0_wp
            self%dx(:, 1:self%n) = a
            i0 = 1
        end if
        call pair_derivative(self%n, self%nm, i0, self%g, self%m, self%x, self%dx, self%dax)
        if (self%coords == PLANETS_JACOBI) then
            call planets_bary_to_jacobi(self%n, self%m, self%eta, self%dax, g, z)
            do k = 1, self%n
                r2 = sum(q(:, k)**2)
                qa = sum(q(:, k) * a(:, k))
                g(:, k) = g(:, k) + (self%gmk(k) / (r2 * sqrt(r2))) * &
                          (a(:, k) - (3.0_wp * qa / r2) * q(:, k))
            end do
        else
            g = self%dax(:, 1:self%n)
        end if
        g = 2.0_wp * g
    end subroutine planets_gradient

    !> Newtonian accelerations ax(:, i0:n) of the bodies i0..n from the massive bodies
    !> i0..nm (test particles nm+1..n feel them and act on nothing).
    pure subroutine pair_field(n, nm, i0, g, m, x, ax)
        integer, intent(in) :: n, nm, i0
        real(wp), intent(in) :: g, m(0:n), x(3, 0:n)
        real(wp), intent(out) :: ax(3, 0:n)
        real(wp) :: d(3), r2, f
        integer :: i, j
        ax = 0.0_wp
        do i = i0, nm
            do j = i + 1, nm
                d = x(:, j) - x(:, i)
                r2 = d(1)**2 + d(2)**2 + d(3)**2
                f = g / (r2 * sqrt(r2))
                ax(:, i) = ax(:, i) + (f * m(j)) * d
                ax(:, j) = ax(:, j) - (f * m(i)) * d
            end do
        end do
        do j = nm + 1, n
            do i = i0, nm
                d = x(:, i) - x(:, j)
                r2 = d(1)**2 + d(2)**2 + d(3)**2
                ax(:, j) = ax(:, j) + (g * m(i) / (r2 * sqrt(r2))) * d
            end do
        end do
    end subroutine pair_field

    !> The derivative dax of `pair_field` along the displacement dx.
    pure subroutine pair_derivative(n, nm, i0, g, m, x, dx, dax)
        integer, intent(in) :: n, nm, i0
        real(wp), intent(in) :: g, m(0:n), x(3, 0:n), dx(3, 0:n)
        real(wp), intent(out) :: dax(3, 0:n)
        real(wp) :: d(3), dd(3), w(3), r2, f
        integer :: i, j
        dax = 0.0_wp
        do i = i0, nm
            do j = i + 1, nm
                d = x(:, j) - x(:, i)
                dd = dx(:, j) - dx(:, i)
                r2 = d(1)**2 + d(2)**2 + d(3)**2
                f = g / (r2 * sqrt(r2))
                w = f * (dd - (3.0_wp * sum(d * dd) / r2) * d)
                dax(:, i) = dax(:, i) + m(j) * w
                dax(:, j) = dax(:, j) - m(i) * w
            end do
        end do
        do j = nm + 1, n
            do i = i0, nm
                d = x(:, i) - x(:, j)
                dd = dx(:, i) - dx(:, j)
                r2 = d(1)**2 + d(2)**2 + d(3)**2
                f = g * m(i) / (r2 * sqrt(r2))
                dax(:, j) = dax(:, j) + f * (dd - (3.0_wp * sum(d * dd) / r2) * d)
            end do
        end do
    end subroutine pair_derivative

    !> After a step failed with FSYM_ERR_MODEL: a close encounter found by the last kick is
    !> the library status FSYM_ERR_ENCOUNTER, and the message names the pair (or, after a
    !> failed Kepler solve, the body); a failure of the `extra` model is left as it is.
    subroutine planets_failure(self, code, msg)
        class(planets_model_t), intent(in) :: self   !! the model
        integer, intent(inout) :: code               !! FSYM_ERR_MODEL on entry
        character(len=*), intent(inout) :: msg       !! the model's text
        if (self%failed == PLANETS_ENCOUNTER) code = FSYM_ERR_ENCOUNTER
        if (self%failed /= 0) msg = self%message
        if (.not. allocated(self%m)) msg = 'planets: the model was never set up (call init first)'
    end subroutine planets_failure

    !> True, with stat = PLANETS_NOT_SET_UP, for a model that was never set up.
    logical function not_set_up(self, stat)
        class(planets_model_t), intent(in) :: self
        integer, intent(out) :: stat
        not_set_up = .not. allocated(self%m)
        stat = merge(PLANETS_NOT_SET_UP, 0, not_set_up)
    end function not_set_up

    !> Fail with PLANETS_ENCOUNTER when a massive pair, or a test particle and a massive body,
    !> are within `hill` mutual Hill radii (inertial positions in self%x).
    subroutine check_encounters(self, stat)
        type(planets_model_t), intent(inout) :: self
        integer, intent(inout) :: stat
        real(wp) :: d2, lim
        integer :: i, j
        do i = 1, self%n
            self%rh(i) = norm2(self%x(:, i) - self%x(:, 0))
        end do
        do i = 1, self%nm
            do j = i + 1, self%n
                d2 = sum((self%x(:, j) - self%x(:, i))**2)
                lim = self%hill * ((self%m(i) + self%m(j)) / (3.0_wp * self%m0))**(1.0_wp &
                      / 3.0_wp) * 0.5_wp * (self%rh(i) + self%rh(j))
                if (d2 < lim * lim) then
                    self%encounter_i = i
                    self%encounter_j = j
                    self%message = 'planets: close encounter of bodies '//fsym_int_text(i)// &
                                   ' and '//fsym_int_text(j)//' (within the Hill limit)'
                    stat = PLANETS_ENCOUNTER
                    self%failed = stat
                    return
                end if
            end do
        end do
    end subroutine check_encounters

end module fsym_planets
