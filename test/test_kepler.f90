!> Tests of the Kepler module against finite differences, conservation laws and the exact
!> solution.
module test_kepler
    use fsym
    use testing
    implicit none
    private
    public :: collect_kepler

contains

    function collect_kepler() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('kepler: acceleration = -grad V (finite differences, 2D and 3D)', t_force), &
            new_test('kepler: gradient term = grad |a|^2 (finite differences)', t_gradient), &
            new_test('kepler: paper orbit elements e = 0.9, E0 = -0.095, P', t_elements), &
            new_test('kepler: exact solution conserves E, L, LRL and has dq/dt = v', t_exact), &
            new_test('kepler: exact solution agrees with a fine A6 integration', t_exact_vs_a6)]
    end function collect_kepler

    subroutine t_force(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q(3), a(3), qp(3), qm(3), fd
        integer :: k, d
        real(wp), parameter :: hh = 1e-5_wp
        do d = 2, 3
            q(1:3) = [0.7_wp, -1.3_wp, 0.4_wp]
            call kepler_acceleration(q(1:d), a(1:d), mu=2.5_wp)
            do k = 1, d
                qp = q; qm = q
                qp(k) = q(k) + hh; qm(k) = q(k) - hh
                fd = -(kepler_potential(qp(1:d), 2.5_wp) - kepler_potential(qm(1:d), 2.5_wp)) &
                     / (2 * hh)
                call check_close(err, a(k), fd, 1e-8_wp, 'a vs -dV/dq')
            end do
        end do
    end subroutine t_force

    subroutine t_gradient(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q(3), g(3), qp(3), qm(3), ap(3), am(3), fd
        type(kepler_model_t) :: m
        real(wp) :: qq(3, 1), aa(3, 1), gg(3, 1)
        integer :: k, st
        real(wp), parameter :: hh = 1e-5_wp
        q = [0.9_wp, 0.2_wp, -0.5_wp]
        call kepler_gradient(q, g)
        do k = 1, 3
            qp = q; qm = q
            qp(k) = q(k) + hh; qm(k) = q(k) - hh
            call kepler_acceleration(qp, ap); call kepler_acceleration(qm, am)
            fd = (sum(ap**2) - sum(am**2)) / (2 * hh)
            call check_close(err, g(k), fd, 1e-7_wp * max(1.0_wp, abs(fd)), 'g vs d|a|^2/dq')
        end do
        qq(:, 1) = q; st = 0
        call m%acceleration(qq, aa, st)
        call m%gradient(qq, aa, gg, st)
        call check(err, maxval(abs(gg(:, 1) - g)) < 1e-13_wp * maxval(abs(g)), 'model gradient')
        call check_close(err, g(1), -4.0_wp * q(1) / sum(q**2)**3, 1e-13_wp, '-4q/r^6')
    end subroutine t_gradient

    subroutine t_elements(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q(2), v(2), p, a, e, pp
        integer :: st
        call kepler_paper_orbit(q, v, p)
        call kepler_elements(q, v, a, e, pp, st)
        call check(err, st == 0, 'elements status')
        call check_close(err, e, 0.9_wp, 1e-14_wp, 'e')
        call check_close(err, a, 100.0_wp / 19.0_wp, 1e-13_wp, 'a')
        call check_close(err, kepler_energy(q, v), -0.095_wp, 1e-15_wp, 'E0')
        call check_close(err, pp, p, 1e-12_wp, 'period')
        call check_close(err, kepler_angular_momentum_2d(q, v), 1.0_wp, 1e-15_wp, 'L')
        call kepler_elements([1.0_wp, 0.0_wp], [0.0_wp, 2.0_wp], a, e, pp, st)
        call check(err, st == FSYM_ERR_NOT_ELLIPTIC, 'unbound orbit refused')
    end subroutine t_elements

    subroutine t_exact(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: q0(2), v0(2), q(2), v(2), qp(2), vp(2), qm(2), vm(2), p, t, l0(2), l(2)
        real(wp), parameter :: dt = 1e-4_wp
        integer :: k, st
        call kepler_paper_orbit(q0, v0, p)
        call kepler_lrl(q0, v0, l0)
        do k = 1, 13
            t = p * k / 13.0_wp + 0.37_wp * k
            call kepler_exact(q0, v0, t, q, v, st)
            call check(err, st == 0, 'exact status')
            call check_close(err, kepler_energy(q, v), -0.095_wp, 1e-13_wp, 'exact E')
            call check_close(err, kepler_angular_momentum_2d(q, v), 1.0_wp, 1e-12_wp, 'exact L')
            call kepler_lrl(q, v, l)
            call check(err, maxval(abs(l - l0)) < 1e-12_wp, 'exact LRL')
            call kepler_exact(q0, v0, t + dt, qp, vp, st)
            call kepler_exact(q0, v0, t - dt, qm, vm, st)
            call check(err, maxval(abs((qp - qm) / (2 * dt) - v)) < 1e-6_wp, 'exact dq/dt = v')
            call check(err, maxval(abs((vp - vm) / (2 * dt) + q / sum(q**2)**1.5_wp)) < 1e-5_wp, &
                       'exact dv/dt = a')
        end do
        call kepler_exact(q0, v0, p, q, v, st)
        call check(err, maxval(abs(q - q0)) < 1e-10_wp, 'exact returns after one period')
        call kepler_exact(q0, v0, 0.5_wp * p, q, v, st)
        call check_close(err, q(1), -10.0_wp / 19.0_wp, 1e-9_wp, &
                         'pericentre at P/2 is (-a(1-e), 0)')
    end subroutine t_exact

    subroutine t_exact_vs_a6(err)
        character(len=:), allocatable, intent(out) :: err
        type(kepler_model_t) :: m
        type(integrator_t) :: it
        real(wp) :: q(2, 1), v(2, 1), q0(2), v0(2), qe(2), ve(2), p
        integer :: st
        call kepler_paper_orbit(q0, v0, p)
        q(:, 1) = q0; v(:, 1) = v0
        call it%init_by_name('A6', m, 2, 1, st)
        call it%run(m, q, v, p / 20000.0_wp, 7000_ik, st)
        call kepler_exact(q0, v0, it%time(), qe, ve, st)
        call check(err, maxval(abs(q(:, 1) - qe)) < 1e-9_wp, 'A6 vs exact position')
        call check(err, maxval(abs(v(:, 1) - ve)) < 1e-9_wp, 'A6 vs exact velocity')
    end subroutine t_exact_vs_a6

end module test_kepler
