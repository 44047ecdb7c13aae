!> Tests of the gravitational N-body model: forces and the gradient term against central
!> finite differences, momentum balance, and energy behaviour of A (true gradient) and A'.
module test_nbody
    use fsym
    use testing
    implicit none
    private
    public :: collect_nbody

    integer, parameter :: nb = 5

contains

    function collect_nbody() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('nbody: a_i = -(1/m_i) dV/dq_i (finite differences)', t_force), &
            new_test('nbody: gradient term = (1/m_j) d/dq_j sum m_i |a_i|^2 (FD)', t_gradient), &
            new_test('nbody: sum m_i a_i = 0 and sum m_i g_i = 0', t_balance), &
            new_test('nbody: A (true gradient) and A'' conserve energy, 4th order', t_energy)]
    end function collect_nbody

    !> A fixed, irregular configuration of nb bodies.
    subroutine config(m, q)
        real(wp), intent(out) :: m(nb), q(3, nb)
        integer :: i
        m = [1.0_wp, 0.3_wp, 0.05_wp, 0.7_wp, 0.01_wp]
        do i = 1, nb
            q(:, i) = [cos(1.7_wp * i), sin(2.3_wp * i) + 0.2_wp * i, 0.5_wp * cos(0.9_wp * i**2)]
        end do
    end subroutine config

    subroutine t_force(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: m(nb), q(3, nb), a(3, nb), qp(3, nb), qm(3, nb), fd, eps
        real(wp), parameter :: hh = 1e-6_wp, gc = 0.8_wp
        integer :: i, k, ie
        call config(m, q)
        do ie = 0, 1
            eps = 0.1_wp * ie
            call fsym_nbody_accel(nb, m, gc, eps, q, a)
            do i = 1, nb
                do k = 1, 3
                    qp = q; qm = q
                    qp(k, i) = q(k, i) + hh; qm(k, i) = q(k, i) - hh
                    fd = -(fsym_nbody_potential(nb, m, gc, eps, qp) - &
                           fsym_nbody_potential(nb, m, gc, eps, qm)) / (2 * hh * m(i))
                    call check_close(err, a(k, i), fd, 1e-6_wp * max(1.0_wp, abs(fd)), &
                                     'a vs -dV/dq / m')
                end do
            end do
        end do
    end subroutine t_force

    !> S(q) = sum_i m_i |a_i(q)|^2.
    real(wp) function big_s(m, gc, eps, q)
        real(wp), intent(in) :: m(nb), gc, eps, q(3, nb)
        real(wp) :: a(3, nb)
        integer :: i
        call fsym_nbody_accel(nb, m, gc, eps, q, a)
        big_s = 0.0_wp
        do i = 1, nb
            big_s = big_s + m(i) * sum(a(:, i)**2)
        end do
    end function big_s

    subroutine t_gradient(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: m(nb), q(3, nb), a(3, nb), g(3, nb), qp(3, nb), qm(3, nb), fd, eps
        real(wp), parameter :: hh = 1e-6_wp, gc = 0.8_wp
        type(nbody_model_t) :: model
        real(wp) :: g2(3, nb)
        integer :: i, k, ie, st
        call config(m, q)
        do ie = 0, 1
            eps = 0.1_wp * ie
            call fsym_nbody_accel(nb, m, gc, eps, q, a)
            call fsym_nbody_gradient(nb, m, gc, eps, q, a, g)
            do i = 1, nb
                do k = 1, 3
                    qp = q; qm = q
                    qp(k, i) = q(k, i) + hh; qm(k, i) = q(k, i) - hh
                    fd = (big_s(m, gc, eps, qp) - big_s(m, gc, eps, qm)) / (2 * hh * m(i))
                    call check_close(err, g(k, i), fd, 1e-5_wp * max(1.0_wp, abs(fd)), &
                                     'g vs (1/m) dS/dq')
                end do
            end do
        end do
        ! the type-bound form gives the same numbers
        call model%init(m, gc, eps=0.1_wp, stat=st)
        call check(err, st == FSYM_SUCCESS, 'init')
        st = 0
        call model%acceleration(q, a, st)
        call model%gradient(q, a, g2, st)
        call check(err, st == 0 .and. all(g2 == g), 'type-bound gradient differs')
        ! bad input is rejected with a status
        call model%init([1.0_wp, -1.0_wp], gc, stat=st)
        call check(err, st == FSYM_ERR_BAD_PARAMETER, 'negative mass accepted')
        st = 0
        call model%acceleration(q(:, 1:2), a(:, 1:2), st)
        call check(err, st == FSYM_ERR_SHAPE, 'shape mismatch not reported')
    end subroutine t_gradient

    subroutine t_balance(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: m(nb), q(3, nb), a(3, nb), g(3, nb), pa(3), pg(3)
        integer :: k
        call config(m, q)
        call fsym_nbody_accel(nb, m, 1.0_wp, 0.0_wp, q, a)
        call fsym_nbody_gradient(nb, m, 1.0_wp, 0.0_wp, q, a, g)
        do k = 1, 3
            pa(k) = sum(m * a(k, :))
            pg(k) = sum(m * g(k, :))
        end do
        call check(err, maxval(abs(pa)) < 1e-13_wp * maxval(abs(a)), 'sum m a /= 0')
        call check(err, maxval(abs(pg)) < 1e-12_wp * maxval(abs(g)), 'sum m g /= 0')
    end subroutine t_balance

    !> Three bodies, a short run: the energy error of A and A' shrinks ~16x when h halves
    !> and stays small; C runs with the true gradient too.
    subroutine t_energy(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=4), parameter :: names(3) = [character(len=4) :: 'A', 'A''', 'C']
        real(wp) :: q(3, 3), v(3, 3), e0, de(2), ratio
        type(nbody_model_t) :: model
        type(integrator_t) :: it
        character(len=200) :: msg
        integer :: km, kh, st, k
        call model%init([1.0_wp, 1.0e-3_wp, 1.0e-4_wp], 1.0_wp, stat=st)
        do km = 1, size(names)
            do kh = 1, 2
                call start(q, v)
                e0 = model%energy(q, v)
                call it%init_by_name(names(km), model, 3, 3, st, msg)
                call check(err, st == FSYM_SUCCESS, 'init '//trim(names(km)))
                if (st /= FSYM_SUCCESS) return
                de(kh) = 0.0_wp
                do k = 1, 200 * kh
                    call it%step(model, q, v, 0.05_wp / kh, st, msg)
                    if (st /= FSYM_SUCCESS) exit
                    de(kh) = max(de(kh), abs(model%energy(q, v) / e0 - 1.0_wp))
                end do
                call check(err, st == FSYM_SUCCESS, 'step '//trim(names(km)))
            end do
            ratio = de(1) / de(2)
            call note(trim(names(km))//': max |dE/E| h=0.05 '//fmt(de(1))//', h=0.025 '// &
                      fmt(de(2))//', ratio '//fmt(ratio))
            call check(err, de(1) < 1e-6_wp, trim(names(km))//' energy error too large')
            call check(err, ratio > 10.0_wp .and. ratio < 25.0_wp, &
                       trim(names(km))//' energy error not 4th order')
        end do
    contains
        subroutine start(q, v)
            real(wp), intent(out) :: q(3, 3), v(3, 3)
            q = 0.0_wp; v = 0.0_wp
            q(:, 2) = [1.0_wp, 0.0_wp, 0.0_wp]; v(:, 2) = [0.0_wp, 1.0_wp, 0.05_wp]
            q(:, 3) = [0.0_wp, -1.6_wp, 0.1_wp]; v(:, 3) = [0.78_wp, 0.0_wp, 0.0_wp]
        end subroutine start
    end subroutine t_energy

    function fmt(x) result(s)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=16) :: buf
        write (buf, '(es10.3)') x
        s = trim(adjustl(buf))
    end function fmt

end module test_nbody
