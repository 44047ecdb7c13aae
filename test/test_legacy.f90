!> Tests of the faces for existing codes: the F77-callable layer, reverse communication, the
!> structure-of-arrays adapter and the C API (called in-process) must reproduce the modern
!> `integrator_t` bit for bit on a Sun-and-planets system, and reject bad calls with a status.
module test_legacy
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_null_funptr, &
                                           c_funloc, c_loc, c_long_long, c_char, c_null_char, &
                                           c_f_pointer, c_associated
    use fsym
    use fsym_legacy_api
    use fsym_capi
    use testing
    implicit none
    private
    public :: collect_legacy

    integer, parameter :: nb = 6, nsteps = 100
    real(wp), parameter :: gconst = 2.95912208286e-4_wp, hstep = 10.0_wp
    ! a Sun and five planets on near-circular, slightly inclined orbits (set by make_system)
    real(wp) :: mass(nb), x0(3, nb), v0(3, nb)
    character(len=4), parameter :: methods(6) = [character(len=4) :: 'FR', 'A', 'A''', 'C', &
                                                 'A6', 'BM']

contains

    !> Sun (mass 1, at rest at the origin) and planets k = 1..5 at radius 5 * 1.8**(k-1) AU
    !> with circular speeds, in days and solar masses.
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

    function collect_legacy() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('legacy: F77 layer FSYMST = integrator_t bit for bit', t_f77), &
            new_test('legacy: reverse communication FSYMRC = integrator_t bit for bit', t_rc), &
            new_test('legacy: structure-of-arrays adapter round trip and bits', t_soa), &
            new_test('legacy: short work array, bad id, bad order rejected', t_errors), &
            new_test('legacy: C API (in-process) = integrator_t bit for bit', t_capi)]
    end function collect_legacy

    !> The caller's acceleration routine (classic signature).
    subroutine accel(nd, n, x, a)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n)
        real(wp), intent(out) :: a(nd, n)
        call fsym_nbody_accel(n, mass, gconst, 0.0_wp, x, a)
    end subroutine accel

    !> The caller's gradient-term routine.
    subroutine grad(nd, n, x, a, g)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n), a(nd, n)
        real(wp), intent(out) :: g(nd, n)
        call fsym_nbody_gradient(n, mass, gconst, 0.0_wp, x, a, g)
    end subroutine grad

    !> The modern API: nsteps of method `name`.
    subroutine modern(name, q, v, nf, ng, st)
        character(len=*), intent(in) :: name
        real(wp), intent(out) :: q(3, nb), v(3, nb)
        integer(ik), intent(out) :: nf, ng
        integer, intent(out) :: st
        type(nbody_model_t) :: model
        type(integrator_t) :: it
        integer :: k
        character(len=200) :: msg
        q = x0; v = v0
        call model%init(mass, gconst, stat=st)
        call it%init_by_name(name, model, 3, nb, st, msg)
        if (st /= 0) return
        do k = 1, nsteps
            call it%step(model, q, v, hstep, st, msg)
            if (st /= 0) return
        end do
        nf = it%force_evaluations(); ng = it%gradient_evaluations()
    end subroutine modern

    !> Set up the F77 work arrays for `name`.
    subroutine setup(name, rw, iw, st)
        character(len=*), intent(in) :: name
        real(wp), allocatable, intent(out) :: rw(:)
        integer, allocatable, intent(out) :: iw(:)
        integer, intent(out) :: st
        integer :: meth, lrw, liw
        call FSYMID(name, meth)
        call FSYMWK(meth, 3, nb, lrw, liw, st)
        if (st /= 0) return
        allocate (rw(lrw), iw(liw))
        call FSYMIN(meth, 3, nb, rw, lrw, iw, liw, st)
    end subroutine setup

    subroutine t_f77(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q(3, nb), v(3, nb), x(3, nb), y(3, nb)
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        integer(ik) :: nf, ng
        integer :: k, st, info, lnf, lng
        call make_system()
        do k = 1, size(methods)
            call modern(trim(methods(k)), q, v, nf, ng, st)
            call check(err, st == 0, 'modern '//trim(methods(k)))
            call setup(trim(methods(k)), rw, iw, st)
            call check(err, st == 0, 'setup '//trim(methods(k)))
            if (st /= 0) return
            x = x0; y = v0
            call FSYMST(3, nb, x, y, hstep, nsteps, accel, grad, rw, size(rw), iw, size(iw), info)
            call FSYMNF(rw, size(rw), lnf, lng)
            call check(err, info == 0 .and. iw(7) == nsteps, 'FSYMST '//trim(methods(k)))
            call check(err, all(x == q) .and. all(y == v), 'FSYMST differs: '//trim(methods(k)))
            call check(err, lnf == nf .and. lng == ng, 'counts differ: '//trim(methods(k)))
        end do
    end subroutine t_f77

    subroutine t_rc(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q(3, nb), v(3, nb), x(3, nb), y(3, nb)
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        integer(ik) :: nf, ng
        integer :: k, st, info, step, ireq, ipnt(3), lnf, lng
        call make_system()
        do k = 1, size(methods)
            call modern(trim(methods(k)), q, v, nf, ng, st)
            call setup(trim(methods(k)), rw, iw, st)
            if (st /= 0) then
                call check(err, .false., 'setup '//trim(methods(k))); return
            end if
            x = x0; y = v0
            info = 0
            do step = 1, nsteps
                ireq = 0
                do
                    call FSYMRC(3, nb, x, y, hstep, rw, size(rw), iw, size(iw), ireq, ipnt, info)
                    select case (ireq)
                    case (1)      ! our own force loop at x
                        call fsym_nbody_accel(nb, mass, gconst, 0.0_wp, x, rw(ipnt(2):))
                    case (2)
                        call fsym_nbody_gradient(nb, mass, gconst, 0.0_wp, x, rw(ipnt(3):), &
                                                 rw(ipnt(2):))
                    case (3)
                        call fsym_nbody_accel(nb, mass, gconst, 0.0_wp, rw(ipnt(1):), &
                                              rw(ipnt(2):))
                    case default
                        exit
                    end select
                end do
                if (info /= 0) exit
            end do
            call FSYMNF(rw, size(rw), lnf, lng)
            call check(err, info == 0, 'FSYMRC failed: '//trim(methods(k)))
            call check(err, all(x == q) .and. all(y == v), 'FSYMRC differs: '//trim(methods(k)))
            call check(err, lnf == nf .and. lng == ng, 'counts differ: '//trim(methods(k)))
        end do
    end subroutine t_rc

    subroutine t_soa(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: xh(nb), yh(nb), zh(nb), vxh(nb), vyh(nb), vzh(nb), x(3, nb), y(3, nb)
        real(wp) :: q(3, nb), v(3, nb)
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        integer(ik) :: nf, ng
        integer :: st, info
        call make_system()
        call FSYMUP(nb, x0, xh, yh, zh)
        call FSYMUP(nb, v0, vxh, vyh, vzh)
        call check(err, all(xh == x0(1, :)) .and. all(zh == x0(3, :)), 'unpack')
        call FSYMPK(nb, xh, yh, zh, x)
        call check(err, all(x == x0), 'pack(unpack(x)) /= x')
        ! a SWIFT-like caller: pack, step, unpack
        call FSYMPK(nb, vxh, vyh, vzh, y)
        call setup('BM', rw, iw, st)
        call FSYMST(3, nb, x, y, hstep, nsteps, accel, grad, rw, size(rw), iw, size(iw), info)
        call FSYMUP(nb, x, xh, yh, zh)
        call FSYMUP(nb, y, vxh, vyh, vzh)
        call modern('BM', q, v, nf, ng, st)
        call check(err, info == 0 .and. all(xh == q(1, :)) .and. all(yh == q(2, :)) .and. &
                   all(zh == q(3, :)) .and. all(vzh == v(3, :)), 'SoA state differs')
    end subroutine t_soa

    subroutine t_errors(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: x(3, nb), y(3, nb), rw(5000)
        integer :: iw(200), meth, lrw, liw, info, ireq, ipnt(3)
        character(len=60) :: msg
        call make_system()
        call FSYMID('a prime', meth)
        call check(err, meth == 4, 'FSYMID(a prime) /= 4')
        call FSYMID('no such method', meth)
        call check(err, meth == 0, 'unknown name not 0')
        call FSYMWK(0, 3, nb, lrw, liw, info)
        call check(err, info == FSYM_ERR_UNKNOWN_METHOD, 'id 0 accepted')
        call FSYMWK(3, 3, nb, lrw, liw, info)
        call check(err, info == 0 .and. lrw > 0 .and. lrw < size(rw) .and. liw < size(iw), 'wk')
        call FSYMIN(3, 3, nb, rw, lrw - 1, iw, liw, info)
        call check(err, info == FSYM_ERR_WORK_SIZE, 'short RW accepted')
        call FSYMIN(3, 3, nb, rw, lrw, iw, liw - 1, info)
        call check(err, info == FSYM_ERR_WORK_SIZE, 'short IW accepted')
        call FSYMMS(info, msg)
        call check(err, msg == 'work array too short', 'FSYMMS: '//trim(msg))
        ! not set up: status, no stop
        iw = 0
        x = x0; y = v0
        call FSYMST(3, nb, x, y, hstep, 1, accel, grad, rw, lrw, iw, liw, info)
        call check(err, info == FSYM_ERR_NOT_INITIALIZED, 'FSYMST without FSYMIN')
        ! an integer work array of length 3: refused without writing past it
        iw(1:4) = [11, 12, 13, 14]
        call FSYMST(3, nb, x, y, hstep, 1, accel, grad, rw, lrw, iw(1:3), 3, info)
        call check(err, info == FSYM_ERR_NOT_INITIALIZED .and. &
                   all(iw(1:4) == [11, 12, 13, 14]), 'FSYMST with LIW = 3 wrote into IW')
        call FSYMIN(3, 3, nb, rw, lrw, iw, liw, info)
        call FSYMST(3, nb + 1, x, y, hstep, 1, accel, grad, rw, lrw, iw, liw, info)
        call check(err, info == FSYM_ERR_SHAPE, 'FSYMST with another N')
        ! resuming with a request that was not made
        ireq = 2
        call FSYMRC(3, nb, x, y, hstep, rw, lrw, iw, liw, ireq, ipnt, info)
        call check(err, info == FSYM_ERR_BAD_REQUEST .and. ireq == -1, 'RC out of order')
        ! abandon a step in progress: state restored
        ireq = 0
        call FSYMRC(3, nb, x, y, hstep, rw, lrw, iw, liw, ireq, ipnt, info)
        call check(err, ireq == 1 .and. ipnt(2) > 0, 'RC first request')
        ireq = -1
        call FSYMRC(3, nb, x, y, hstep, rw, lrw, iw, liw, ireq, ipnt, info)
        call check(err, info == 0 .and. all(x == x0) .and. all(y == v0), 'RC abandon')
        ! a zero step is refused with the state unchanged
        call FSYMST(3, nb, x, y, 0.0_wp, 1, accel, grad, rw, lrw, iw, liw, info)
        call check(err, info == FSYM_ERR_BAD_STEP .and. all(x == x0), 'zero step')
    end subroutine t_errors

    !> C callback implemented in Fortran.
    integer(c_int) function c_accel(d, n, q, a, user) bind(C)
        integer(c_int), value :: d, n
        real(c_double), intent(in) :: q(3, n)
        real(c_double), intent(out) :: a(3, n)
        type(c_ptr), value :: user
        integer(c_int), pointer :: calls
        c_accel = 1
        if (d /= 3) return      ! refuse: this callback knows 3D only
        call fsym_nbody_accel(int(n), mass, gconst, 0.0_wp, q, a)
        call c_f_pointer(user, calls)
        calls = calls + 1
        c_accel = 0
    end function c_accel

    integer(c_int) function c_grad(d, n, q, a, g, user) bind(C)
        integer(c_int), value :: d, n
        real(c_double), intent(in) :: q(3, n), a(3, n)
        real(c_double), intent(out) :: g(3, n)
        type(c_ptr), value :: user
        call fsym_nbody_gradient(int(n), mass, gconst, 0.0_wp, q, a, g)
        c_grad = 0
        if (d /= 3 .or. .not. c_associated(user)) c_grad = 1
    end function c_grad

    subroutine t_capi(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp), target :: x(3, nb), y(3, nb)
        real(wp) :: q(3, nb), v(3, nb)
        integer(c_int), target :: calls
        integer(ik) :: nf, ng
        integer(c_long_long), target :: cnf, cng
        type(c_ptr), target :: h
        integer :: k, st
        character(kind=c_char, len=16), target :: name
        call make_system()
        do k = 1, size(methods)
            call modern(trim(methods(k)), q, v, nf, ng, st)
            name = trim(methods(k))//c_null_char
            calls = 0
            st = fsym_c_create(c_loc(name), 3_c_int, int(nb, c_int), c_funloc(c_accel), &
                               c_funloc(c_grad), c_loc(calls), c_loc(h))
            call check(err, st == 0, 'fsym_create '//trim(methods(k)))
            if (st /= 0) return
            x = x0; y = v0
            st = fsym_c_step(h, c_loc(x), c_loc(y), real(hstep, c_double), int(nsteps, c_int))
            st = st + fsym_c_counts(h, c_loc(cnf), c_loc(cng))
            call fsym_c_destroy(h)
            call check(err, st == 0 .and. all(x == q) .and. all(y == v), &
                       'C API differs: '//trim(methods(k)))
            call check(err, cnf == nf .and. cng == ng .and. calls == nf, 'C API counts')
        end do
        ! no gradient callback: A refused with a status, A' fine
        name = 'A'//c_null_char
        st = fsym_c_create(c_loc(name), 3_c_int, int(nb, c_int), c_funloc(c_accel), &
                           c_null_funptr, c_null_ptr, c_loc(h))
        call check(err, st == FSYM_ERR_NO_GRADIENT .and. .not. c_associated(h), 'A without grad')
        name = 'nonsense'//c_null_char
        st = fsym_c_create(c_loc(name), 3_c_int, int(nb, c_int), &
                           c_funloc(c_accel), c_null_funptr, c_null_ptr, c_loc(h))
        call check(err, st == FSYM_ERR_UNKNOWN_METHOD, 'unknown name')
        st = fsym_c_step(c_null_ptr, c_loc(x), c_loc(y), 1.0_c_double, 1_c_int)
        call check(err, st == FSYM_ERR_NOT_INITIALIZED, 'NULL handle')
        ! a callback that reports failure: status FSYM_ERR_MODEL, state unchanged
        name = 'FR'//c_null_char
        st = fsym_c_create(c_loc(name), 2_c_int, int(nb, c_int), c_funloc(c_accel), &
                           c_null_funptr, c_loc(calls), c_loc(h))
        x = x0; y = v0
        st = st + fsym_c_step(h, c_loc(x), c_loc(y), 1.0_c_double, 3_c_int)
        call fsym_c_destroy(h)
        call check(err, st == FSYM_ERR_MODEL .and. all(x == x0) .and. all(y == v0), &
                   'failing callback')
    end subroutine t_capi

end module test_legacy
