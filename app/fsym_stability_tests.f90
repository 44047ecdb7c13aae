!> Linear stability: closed forms (T2, Forest-Ruth), the stage-array oscillator map against
!> the integrator, x* of every method against direct integration just below and above it,
!> the stiff chain's stable step against x*/omega_max, and the FPU model's gradient term.
!>
!> Study tests: they use the study modules of app/ (fpm lets only sources in app/ use them), so
!> they run as the fpm test `fsym-study-tests` (driver `fsym_study_tests.f90`).
module fsym_stability_tests
    use fsym
    use fsym_linear_stability
    use fsym_fpu
    use fsym_stability_runs
    use fsym_study_testing, only: test_t, new_test, check, check_close, note
    implicit none
    private
    public :: collect_stability

contains

    function collect_stability() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('stability: T2 interval x* = 2', t_t2), &
            new_test('stability: Forest-Ruth interval from its trace polynomial', t_fr), &
            new_test('stability: A and C intervals 2 sqrt 3 and 2 sqrt 2', t_ac), &
            new_test('stability: stage-array map equals the integrator''s step', t_map), &
            new_test('stability: x* of every method vs integration below/above', t_cross), &
            new_test('stability: stiff chain step limit = x*/omega_max (dgeev)', t_chain), &
            new_test('stability: FPU gradient term vs finite differences', t_fpu_grad), &
            new_test('stability: near collisions refused or finite, never NaN', t_collision), &
            new_test('stability: FPU run keeps H and I; Kepler step search', t_runs)]
    end function collect_stability

    subroutine t_t2(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: xs
        call fsym_stability_interval(fsym_scheme_t2(), xs)
        call check_close(err, xs, 2.0_wp, 1.0e-12_wp, 'T2 x*')
        ! trace = 2 - x^2 exactly
        call check_close(err, fsym_oscillator_trace(fsym_scheme_t2(), 0.7_wp), &
                         2.0_wp - 0.49_wp, 1.0e-15_wp, 'T2 trace at 0.7')
    end subroutine t_t2

    !> FR = T2(a1 h) T2(a0 h) T2(a1 h): multiplying the three DKD leapfrog matrices by hand
    !> (sympy) gives trace = 2 - x^2 + x^4/12 + c6 x^6 with
    !> c6 = (2 + 2^(1/3) - 2 2^(2/3)) / (864 2^(2/3) - 288 2^(1/3) - 1008) ~ 0.1295;
    !> the trace never reaches -2 and comes back to +2 at y = x^2 solving c6 y^2 + y/12 - 1 = 0.
    subroutine t_fr(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: xs, c6, y, t, x
        integer :: k
        t = 2.0_wp**(1.0_wp / 3.0_wp)
        c6 = (2.0_wp + t - 2.0_wp * t**2) / (864.0_wp * t**2 - 288.0_wp * t - 1008.0_wp)
        y = (-1.0_wp / 12.0_wp + sqrt(1.0_wp / 144.0_wp + 4.0_wp * c6)) / (2.0_wp * c6)
        call fsym_stability_interval(fsym_scheme_fr(), xs)
        call check_close(err, xs, sqrt(y), 1.0e-12_wp, 'FR x* vs closed form')
        call check_close(err, xs, 1.5734019474345_wp, 1.0e-12_wp, 'FR x* ~ 1.5734019474345')
        do k = 1, 7
            x = 0.25_wp * k
            call check_close(err, fsym_oscillator_trace(fsym_scheme_fr(), x), &
                             2.0_wp - x**2 + x**4 / 12.0_wp + c6 * x**6, 1.0e-12_wp, &
                             'FR trace polynomial')
        end do
        call note_real('FR x* = ', xs)
    end subroutine t_fr

    !> Traces multiplied out (sympy): A: trace + 2 = -(x^2 - 12)^3/432, so x* = 2 sqrt 3 with a
    !> flat crossing; C: trace + 2 = (x^2 - 8)(x^6 - 48x^4 + 1152x^2 - 9216)/18432, x* = 2 sqrt 2.
    subroutine t_ac(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: xs, x
        integer :: k
        call fsym_stability_interval(fsym_scheme_a(), xs)
        call check_close(err, xs, 2.0_wp * sqrt(3.0_wp), 1.0e-4_wp, 'A x*')
        call fsym_stability_interval(fsym_scheme_c(), xs)
        call check_close(err, xs, 2.0_wp * sqrt(2.0_wp), 1.0e-12_wp, 'C x*')
        do k = 1, 6
            x = 0.5_wp * k
            call check_close(err, fsym_oscillator_trace(fsym_scheme_a(), x), &
                             -2.0_wp - (x**2 - 12.0_wp)**3 / 432.0_wp, 1.0e-12_wp, 'A trace')
        end do
    end subroutine t_ac

    subroutine t_map(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(oscillator_model_t) :: osc
        type(scheme_t) :: s
        real(wp) :: m(2, 2), mm(2, 2)
        integer :: k, st
        character(len=256) :: msg
        names = fsym_catalogue()
        do k = 1, size(names)
            call fsym_scheme_by_name(names(k), s, st, msg)
            call check(err, st == 0, 'scheme '//trim(names(k)))
            call fsym_oscillator_map(s, 0.7_wp, m)
            call fsym_linear_step_map(names(k), osc, 1, 1, 0.7_wp, mm, st, msg)
            call check(err, st == 0, 'map of '//trim(names(k))//': '//trim(msg))
            call check(err, maxval(abs(m - mm)) < 1.0e-13_wp, 'map mismatch '//trim(names(k)))
            call check(err, abs(m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1) - 1.0_wp) < 1.0e-13_wp, &
                       'det /= 1 for '//trim(names(k)))
        end do
    end subroutine t_map

    !> Oscillator omega = 1, h = x: bounded after many steps at 0.99 x*, growing at 1.01 x*.
    subroutine t_cross(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(scheme_t) :: s
        type(oscillator_model_t) :: osc
        real(wp) :: xs, xn, below, above
        integer :: k, st
        character(len=256) :: msg
        character(len=96) :: line
        names = fsym_method_names()
        do k = 1, size(names)
            if (names(k) == 'RKN') then
                call fsym_stable_step('RKN', osc, 1, 1, 6.0_wp, xs, st, msg)
                call check(err, st == 0, 'RKN stable step: '//trim(msg))
                xn = 2.0_wp * xs
            else
                call fsym_scheme_by_name(names(k), s, st, msg)
                xn = 2.0_wp * xs
                call fsym_stability_interval(s, xs, xnext=xn)
            end if
            ! just above: inside the first instability window, however narrow
            call fsym_oscillator_growth(names(k), 0.99_wp * xs, 20000, below)
            call fsym_oscillator_growth(names(k), xs + min(0.01_wp * xs, 0.5_wp * (xn - xs)), &
                                        20000, above)
            write (line, '(a10,a,f9.6,a,es9.2,a,es9.2)') names(k), ' x* =', xs, &
                '  growth below', below, ' above', above
            call note(trim(line))
            call check(err, below < 1.0e2_wp, 'not bounded below x*: '//trim(names(k)))
            call check(err, above > 1.0e6_wp, 'not growing above x*: '//trim(names(k)))
        end do
    end subroutine t_cross

    subroutine t_chain(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=4), parameter :: names(5) = [character(len=4) :: 'T2', 'FR', 'A', 'C', 'RKN']
        type(spring_chain_model_t) :: chain
        type(oscillator_model_t) :: osc
        type(scheme_t) :: s
        real(wp) :: omega(6), xs, hs, pred
        integer :: k, st
        character(len=256) :: msg
        character(len=96) :: line
        call fsym_linear_chain(6, 1.0e4_wp, chain, st, msg)
        call fsym_linear_frequencies(chain, 1, 6, omega, st, msg)
        call check(err, st == 0, 'frequencies: '//trim(msg))
        call check(err, (omega(6) / omega(1))**2 > 1.0e4_wp, 'stiffness ratio')
        do k = 1, size(names)
            if (names(k) == 'RKN') then
                call fsym_stable_step('RKN', osc, 1, 1, 6.0_wp, xs, st, msg)
            else
                call fsym_scheme_by_name(names(k), s, st, msg)
                call fsym_stability_interval(s, xs)
            end if
            pred = xs / omega(6)
            call fsym_stable_step(names(k), chain, 1, 6, 2.0_wp * pred, hs, st, msg)
            call check(err, st == 0, 'chain stable step: '//trim(msg))
            write (line, '(a4,a,es15.8,a,es15.8)') names(k), ' predicted h* =', pred, &
                ' dgeev h* =', hs
            call note(trim(line))
            ! rho <= 1 + 1e-6 is reached within ~1e-4 relative where the trace meets 2 flatly (A)
            call check(err, abs(hs - pred) <= 3.0e-4_wp * pred, 'chain limit '//trim(names(k)))
        end do
    end subroutine t_chain

    subroutine t_fpu_grad(err)
        character(len=:), allocatable, intent(out) :: err
        type(spring_chain_model_t) :: fpu
        real(wp) :: q(1, 6), v(1, 6), a(1, 6), g(1, 6), ap(1, 6), am(1, 6), fd(1, 6)
        real(wp) :: iosc(3), e0, ep, em, del
        integer :: j, st
        call fsym_fpu_chain(3, 50.0_wp, fpu, st)
        call fsym_fpu_initial(50.0_wp, q, v)
        call fsym_fpu_oscillatory(50.0_wp, q, v, iosc)
        call check_close(err, iosc(1), 1.0_wp, 1.0e-14_wp, 'I_1(0)')
        call check_close(err, iosc(2) + iosc(3), 0.0_wp, 0.0_wp, 'I_2(0) + I_3(0)')
        q(1, :) = q(1, :) + [0.1_wp, -0.2_wp, 0.3_wp, 0.05_wp, -0.1_wp, 0.2_wp]
        st = 0
        call fpu%acceleration(q, a, st)
        call fpu%gradient(q, a, g, st)
        del = 1.0e-5_wp
        do j = 1, 6
            q(1, j) = q(1, j) + del
            call fpu%acceleration(q, ap, st)
            call fpu%potential(q, ep, st)
            q(1, j) = q(1, j) - 2.0_wp * del
            call fpu%acceleration(q, am, st)
            call fpu%potential(q, em, st)
            q(1, j) = q(1, j) + del
            fd(1, j) = (sum(ap**2) - sum(am**2)) / (2.0_wp * del)
            call check_close(err, -(ep - em) / (2.0_wp * del), a(1, j), 1.0e-5_wp * 2500.0_wp, &
                             'force = -grad V')
        end do
        call fpu%potential(q, e0, st)
        call check(err, maxval(abs(fd - g)) <= 1.0e-7_wp * maxval(abs(g)), 'gradient term')
    end subroutine t_fpu_grad

    !> Every method through pericentre 1e-9, from r = 0, and in radial infall: each run ends
    !> either refused with a status and message or with a finite state.
    subroutine t_collision(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(kepler_run_t) :: run
        real(wp) :: q0(2, 3), v0(2, 3)
        integer :: k, c, nrefused
        names = fsym_method_names()
        call kepler_elliptic_orbit(1.0_wp - 1.0e-9_wp, q0(:, 1), v0(:, 1))
        q0(:, 2) = 0.0_wp; v0(:, 2) = [0.0_wp, 1.0_wp]
        q0(:, 3) = [1.0_wp, 0.0_wp]; v0(:, 3) = 0.0_wp
        nrefused = 0
        do k = 1, size(names)
            do c = 1, 3
                call fsym_kepler_run(names(k), q0(:, c), v0(:, c), 200_ik, 1_ik, run)
                if (run%outcome == RUN_REFUSED) then
                    nrefused = nrefused + 1
                    call check(err, run%stat /= 0 .and. len_trim(run%msg) > 0, &
                               'refused without status: '//trim(names(k)))
                end if
                call check(err, run%finite, 'non-finite state kept: '//trim(names(k)))
                call check(err, run%time == real(run%steps, wp) * (2.0_wp * FSYM_PI / 200.0_wp), &
                           'time is not n h: '//trim(names(k)))
            end do
        end do
        call check(err, nrefused > 0, 'no refusal exercised')
    end subroutine t_collision

    !> FPU with C at a quarter of its limit: energy error small, oscillatory energy nearly
    !> kept; the Kepler search at e = 0.5 finds a step count, and errors fall along the grid.
    subroutine t_runs(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: samples(5, 11), dh, di, xs, errs(20)
        integer(ik) :: needed, broken, grid(20)
        integer :: ns, st, ng, outcomes(20)
        character(len=256) :: msg
        call fsym_stability_interval(fsym_scheme_c(), xs)
        call fsym_fpu_run('C', 3, 50.0_wp, 0.25_wp * xs / 50.0_wp, 1414_ik, 141_ik, samples, ns, &
                          dh, di, st, msg)
        call check(err, st == 0 .and. ns == 11, 'FPU run: '//trim(msg))
        call check(err, dh < 1.0e-3_wp, 'FPU energy error with C at 0.25 x*')
        call check(err, di < 0.1_wp, 'FPU oscillatory energy with C at 0.25 x*')
        call check_close(err, samples(3, 1), 1.0_wp, 1.0e-12_wp, 'I_1 in the first sample')
        call fsym_kepler_steps_needed('C', 0.5_wp, 1.0e-6_wp, 16_ik, 4096_ik, needed, broken, &
                                      ng, grid, errs, outcomes)
        call check(err, needed > 16 .and. needed <= 4096, 'no step count found at e = 0.5')
        call check(err, errs(ng) < 1.0e-6_wp .and. errs(1) > errs(ng), 'errors do not fall')
        call check(err, broken == 0, 'C broke down at e = 0.5')
    end subroutine t_runs

    subroutine note_real(label, x)
        character(len=*), intent(in) :: label
        real(wp), intent(in) :: x
        character(len=64) :: buf
        write (buf, '(a,f18.15)') label, x
        call note(trim(buf))
    end subroutine note_real

end module fsym_stability_tests
