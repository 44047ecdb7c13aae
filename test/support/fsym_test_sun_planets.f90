!> The test system of the legacy-face tests: a Sun and five planets on near-circular,
!> slightly inclined orbits (days, solar masses, AU), the caller's force routines with the
!> classic F77 signatures and as C callbacks, and the reference run through the modern
!> `integrator_t`.
module fsym_test_sun_planets
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_f_pointer, c_associated
    use fsym, only: wp, ik, integrator_t, nbody_model_t, fsym_nbody_accel, fsym_nbody_gradient
    use fsym_legacy_api, only: FSYMID, FSYMWK, FSYMIN
    implicit none
    private
    public :: nb, nsteps, gconst, hstep, mass, x0, v0, methods
    public :: make_system, accel, grad, modern, setup, c_accel, c_grad

    integer, parameter :: nb = 6              !! bodies (the Sun last)
    integer, parameter :: nsteps = 100        !! steps of every run
    real(wp), parameter :: gconst = 2.95912208286e-4_wp  !! G in AU^3 / (Msun day^2)
    real(wp), parameter :: hstep = 10.0_wp    !! step (days)
    real(wp) :: mass(nb)                      !! masses (solar masses)
    real(wp) :: x0(3, nb)                     !! initial positions (AU)
    real(wp) :: v0(3, nb)                     !! initial velocities (AU/day)
    !> the methods the faces are compared on
    character(len=4), parameter :: methods(6) = [character(len=4) :: 'FR', 'A', 'A''', 'C', &
                                                 'A6', 'BM']

contains

    !> Sun (mass 1, at rest at the origin) and planets k = 1..5 at radius 5 * 1.8**(k-1) AU
    !> with circular speeds.
    subroutine make_system()
        integer :: k
        real(wp) :: r, phi, z
        mass(nb) = 1.0_wp
        x0(:, nb) = 0.0_wp
        v0(:, nb) = 0.0_wp
        do k = 1, nb - 1
            mass(k) = 1.0e-3_wp / k
            r = 5.0_wp * 1.8_wp**(k - 1)
            phi = 2.1_wp * k
            z = 0.02_wp * r * sin(3.0_wp * k)
            x0(:, k) = [r * cos(phi), r * sin(phi), z]
            v0(:, k) = sqrt(gconst / r) * [-sin(phi), cos(phi), 0.01_wp * k]
        end do
    end subroutine make_system

    !> The caller's acceleration routine (classic signature).
    subroutine accel(nd, n, x, a)
        integer, intent(in) :: nd                 !! dimensions (3)
        integer, intent(in) :: n                  !! bodies
        real(wp), intent(in) :: x(nd, n)          !! positions
        real(wp), intent(out) :: a(nd, n)         !! accelerations
        call fsym_nbody_accel(n, mass, gconst, 0.0_wp, x, a)
    end subroutine accel

    !> The caller's gradient-term routine (classic signature).
    subroutine grad(nd, n, x, a, g)
        integer, intent(in) :: nd                 !! dimensions (3)
        integer, intent(in) :: n                  !! bodies
        real(wp), intent(in) :: x(nd, n)          !! positions
        real(wp), intent(in) :: a(nd, n)          !! accelerations at x
        real(wp), intent(out) :: g(nd, n)         !! gradient term
        call fsym_nbody_gradient(n, mass, gconst, 0.0_wp, x, a, g)
    end subroutine grad

    !> The modern API: nsteps of method `name` from (x0, v0).
    subroutine modern(name, q, v, nf, ng, st)
        character(len=*), intent(in) :: name      !! method label
        real(wp), intent(out) :: q(3, nb)         !! final positions
        real(wp), intent(out) :: v(3, nb)         !! final velocities
        integer(ik), intent(out) :: nf            !! force evaluations
        integer(ik), intent(out) :: ng            !! gradient evaluations
        integer, intent(out) :: st                !! status
        type(nbody_model_t) :: model
        type(integrator_t) :: it
        integer :: k
        character(len=200) :: msg
        q = x0; v = v0; nf = 0; ng = 0
        call model%init(mass, gconst, stat=st)
        call it%init_by_name(name, model, 3, nb, st, msg)
        if (st /= 0) return
        do k = 1, nsteps
            call it%step(model, q, v, hstep, st, msg)
            if (st /= 0) return
        end do
        nf = it%force_evaluations(); ng = it%gradient_evaluations()
    end subroutine modern

    !> The F77 work arrays of method `name`, set up for (3, nb).
    subroutine setup(name, rw, iw, st)
        character(len=*), intent(in) :: name          !! method label
        real(wp), allocatable, intent(out) :: rw(:)   !! real work array
        integer, allocatable, intent(out) :: iw(:)    !! integer work array
        integer, intent(out) :: st                    !! status
        integer :: meth, lrw, liw
        call FSYMID(name, meth)
        call FSYMWK(meth, 3, nb, lrw, liw, st)
        if (st /= 0) return
        allocate (rw(lrw), iw(liw))
        call FSYMIN(meth, 3, nb, rw, lrw, iw, liw, st)
    end subroutine setup

    !> C callback implemented in Fortran: counts its calls in `user`.
    integer(c_int) function c_accel(d, n, q, a, user) bind(C)
        integer(c_int), value :: d                 !! dimensions (3 only)
        integer(c_int), value :: n                 !! bodies
        real(c_double), intent(in) :: q(3, n)      !! positions
        real(c_double), intent(out) :: a(3, n)     !! accelerations
        type(c_ptr), value :: user                 !! an int counter of the calls
        integer(c_int), pointer :: calls
        c_accel = 1
        if (d /= 3) return      ! refuse: this callback knows 3D only
        call fsym_nbody_accel(int(n), mass, gconst, 0.0_wp, q, a)
        call c_f_pointer(user, calls)
        calls = calls + 1
        c_accel = 0
    end function c_accel

    !> C gradient callback implemented in Fortran.
    integer(c_int) function c_grad(d, n, q, a, g, user) bind(C)
        integer(c_int), value :: d                 !! dimensions (3 only)
        integer(c_int), value :: n                 !! bodies
        real(c_double), intent(in) :: q(3, n)      !! positions
        real(c_double), intent(in) :: a(3, n)      !! accelerations at q
        real(c_double), intent(out) :: g(3, n)     !! gradient term
        type(c_ptr), value :: user                 !! must not be NULL
        call fsym_nbody_gradient(int(n), mass, gconst, 0.0_wp, q, a, g)
        c_grad = 0
        if (d /= 3 .or. .not. c_associated(user)) c_grad = 1
    end function c_grad


end module fsym_test_sun_planets
