!> The study's diagnostics against analytic cases: energy and precession error coefficients
!> on hand-built state sequences of known energy and known LRL rotation (crossing +-pi), the
!> unwrapping of angle sequences, and the eps vs eps/2 convergence check on a real run.
!> (The HDF5 layer lives in app/ and is tested by the `fsym-h5-tests` program there.)
module test_study
    use fsym
    use testing
    implicit none
    private
    public :: collect_study

contains

    function collect_study() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('study: precession coefficient of known rotations across +-pi', t_rotation), &
            new_test('study: energy coefficient of known energies', t_energy), &
            new_test('study: unwrapping an angle sequence', t_unwrap), &
            new_test('study: A on the paper orbit, coefficients converge eps vs eps/2', t_conv)]
    end function collect_study

    !> (q, v) rotated by angle th.
    pure subroutine rotate(q, v, th, qr, vr)
        real(wp), intent(in) :: q(2), v(2), th
        real(wp), intent(out) :: qr(2), vr(2)
        qr = [cos(th) * q(1) - sin(th) * q(2), sin(th) * q(1) + cos(th) * q(2)]
        vr = [cos(th) * v(1) - sin(th) * v(2), sin(th) * v(1) + cos(th) * v(2)]
    end subroutine rotate

    subroutine t_rotation(err)
        character(len=:), allocatable, intent(out) :: err
        type(coefficient_tracker_t) :: tr
        real(wp) :: q0(2), v0(2), q(2), v(2), th, eps, sgn
        integer :: k, j
        eps = 0.5_wp
        call kepler_paper_orbit(q0, v0)
        ! the LRL vector of the paper orbit points to -x (pericentre), angle pi: any
        ! rotation crosses the branch cut of atan2 at once
        call check_close(err, abs(kepler_lrl_angle(q0, v0)), FSYM_PI, 1.0e-12_wp, 'LRL angle')
        do j = 1, 2
            sgn = merge(1.0_wp, -1.0_wp, j == 1)
            call tr%init(q0, v0, eps)
            do k = 1, 40                     ! 40 x 0.7 rad = 28 rad, four and a half turns
                th = sgn * 0.7_wp * k
                call rotate(q0, v0, th, q, v)
                call tr%update(q, v)
                call check_close(err, tr%precession, th / eps**4, 1.0e-11_wp, 'precession')
                call check_close(err, tr%energy, 0.0_wp, 1.0e-12_wp, 'energy of a rotation')
            end do
            call check_close(err, tr%precession_max, 28.0_wp / eps**4, 1.0e-11_wp, 'max')
        end do
    end subroutine t_rotation

    subroutine t_energy(err)
        character(len=:), allocatable, intent(out) :: err
        type(coefficient_tracker_t) :: tr
        real(wp) :: q0(2), v0(2), e, eps, s, emax
        integer :: k
        eps = 0.1_wp
        call kepler_paper_orbit(q0, v0)
        call tr%init(q0, v0, eps)
        emax = 0.0_wp
        do k = 1, 10
            s = 1.0_wp + 0.01_wp * (-1)**k * k   ! speed scaled: E = s^2 |v|^2/2 - 1/|q|
            e = 0.5_wp * s**2 * 0.01_wp - 0.1_wp
            call tr%update(q0, s * v0)
            call check_close(err, tr%energy, (e + 0.095_wp) / (-0.095_wp * eps**4), &
                             1.0e-9_wp, 'energy coefficient')
            emax = max(emax, abs((e + 0.095_wp) / (-0.095_wp * eps**4)))
            call check_close(err, tr%precession, 0.0_wp, 1.0e-9_wp, 'no precession')
        end do
        call check_close(err, tr%energy_max, emax, 1.0e-9_wp, 'max |energy coefficient|')
        call check_close(err, fsym_energy_coefficient(-0.1_wp, -0.095_wp, 0.1_wp), &
                         (-0.005_wp / (-0.095_wp)) * 1.0e4_wp, 1.0e-9_wp, 'elemental form')
    end subroutine t_energy

    subroutine t_unwrap(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: th(50), raw(50), un(50)
        integer :: k
        do k = 1, size(th)
            th(k) = 3.0_wp - 0.35_wp * k + 0.1_wp * sin(real(k, wp))
            raw(k) = atan2(sin(th(k)), cos(th(k)))
        end do
        call fsym_unwrap_angles(raw, un)
        call check(err, maxval(abs(un - th)) < 1.0e-12_wp, 'unwrapped sequence')
        call check_close(err, fsym_angle_step(3.0_wp, -3.0_wp), 2.0_wp * FSYM_PI - 6.0_wp, &
                         1.0e-15_wp, 'step across pi')
        call check_close(err, fsym_relative_difference(1.0_wp, 1.1_wp), 0.1_wp / 1.1_wp, &
                         1.0e-15_wp, 'relative difference')
        call check_close(err, fsym_relative_difference(0.0_wp, 0.0_wp), 0.0_wp, 0.0_wp, &
                         'relative difference of zeros')
    end subroutine t_unwrap

    subroutine t_conv(err)
        character(len=:), allocatable, intent(out) :: err
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        type(coefficient_tracker_t) :: tr
        real(wp) :: q(2, 1), v(2, 1), p, eco(2), pco(2)
        integer :: m, k, n, st
        character(len=256) :: msg
        character(len=120) :: line
        do m = 1, 2
            n = 2500 * 2**m              ! eps = P/5000 and P/10000
            call kepler_paper_orbit(q(:, 1), v(:, 1), p)
            call fsym_new_stepper('A', kep, 2, 1, s, st, msg)
            call check(err, st == 0, trim(msg))
            if (st /= 0) return
            call tr%init(q(:, 1), v(:, 1), p / n)
            do k = 1, n
                call s%step(kep, q, v, p / n, st, msg)
                call tr%update(q(:, 1), v(:, 1))
            end do
            eco(m) = tr%energy_max
            pco(m) = tr%precession
        end do
        write (line, '(a,2es11.3,a,2es11.3)') 'A: max|E coeff|', eco, '  prec(P)', pco
        call note(trim(line))
        call check(err, fsym_relative_difference(eco(1), eco(2)) < 0.05_wp, &
                   'energy coefficient not converged')
        call check(err, fsym_relative_difference(pco(1), pco(2)) < 0.05_wp, &
                   'precession coefficient not converged')
        call check(err, pco(1) /= 0.0_wp .and. eco(1) > 0.0_wp, 'coefficients vanish')
    end subroutine t_conv

end module test_study
