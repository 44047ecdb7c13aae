!> Tests of the integrators, driven by the catalogue: measured order of every method,
!> symplecticity, reversibility, evaluation counts, caching, compensated summation, and
!> any dimension / any number of particles.
module test_integrator
    use fsym
    use testing
    implicit none
    private
    public :: collect_integrator

contains

    function collect_integrator() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('order: every method on the e = 0.9 Kepler orbit (P/3200..P/12800)', &
                     t_order_kepler), &
            new_test('order: every method on Henon-Heiles (h = 0.2..0.025)', t_order_hh), &
            new_test('symplectic: M^T J M = J for every splitting method; not for RKN', &
                     t_symplectic), &
            new_test('symplectic: extrapolated methods defect ~ h^5 on Henon-Heiles', &
                     t_extrap_defect), &
            new_test('reversible: symmetric methods return under h, -h', t_reversible), &
            new_test('counts: measured evaluations per step match the paper', t_counts), &
            new_test('counts: no gradient work for methods without gradient', t_no_gradient_work), &
            new_test('cache: first-same-as-last survives only an unchanged q', t_fsal_cache), &
            new_test('layout: 3D, n bodies equal n separate 1-body runs bitwise', t_particles), &
            new_test('compensated: Kahan summation lowers round-off energy growth', &
                     t_compensated), &
            new_test('recorder: force points recorded, same result as without', t_recorder), &
            new_test('clock: time is t0 + k h', t_clock)]
    end function collect_integrator

    subroutine new(name, model, d, n, s, err)
        character(len=*), intent(in) :: name
        class(force_model_t), intent(in) :: model
        integer, intent(in) :: d, n
        class(stepper_t), allocatable, intent(inout) :: s
        character(len=:), allocatable, intent(inout) :: err
        integer :: st
        character(len=256) :: msg
        call fsym_new_stepper(name, model, d, n, s, st, msg)
        call check(err, st == 0, 'cannot make '//name//': '//trim(msg))
    end subroutine new

    !> Phase-space error after one period of the paper orbit at h = P/nper.
    real(wp) function kepler_error(name, nper, err) result(e)
        character(len=*), intent(in) :: name
        integer, intent(in) :: nper
        character(len=:), allocatable, intent(inout) :: err
        type(kepler_model_t) :: m
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), p, q0(2), v0(2)
        integer :: st
        call kepler_paper_orbit(q0, v0, p)
        q(:, 1) = q0; v(:, 1) = v0
        call new(name, m, 2, 1, s, err)
        call s%run(m, q, v, p / nper, int(nper, ik), st)
        call check(err, st == 0, name//': run failed')
        e = max(maxval(abs(q(:, 1) - q0)), maxval(abs(v(:, 1) - v0)) * 10.0_wp)
    end function kepler_error

    subroutine t_order_kepler(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        integer, parameter :: nper(3) = [3200, 6400, 12800]
        real(wp) :: e(3), h(3), p(2), expect
        character(len=160) :: line
        integer :: k, j
        names = fsym_method_names()
        h = 1.0_wp / nper
        do k = 1, size(names)
            do j = 1, 3
                e(j) = kepler_error(trim(names(k)), nper(j), err)
            end do
            p = fsym_observed_orders(h, e)
            expect = merge(2.0_wp, 4.0_wp, names(k) == 'T2')
            write (line, '(a,a10,a,3es10.2,a,2f7.3)') 'order kepler ', trim(names(k)), &
                '  err', e, '  p', p
            call note(trim(line))
            call check(err, abs(p(2) - expect) < 0.25_wp, trim(line))
        end do
    end subroutine t_order_kepler

    !> Henon-Heiles state after time 10 at step h.
    subroutine hh_run(name, h, z, err)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: h
        real(wp), intent(out) :: z(4)
        character(len=:), allocatable, intent(inout) :: err
        type(henon_heiles_model_t) :: m
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1)
        integer :: st
        q(:, 1) = [0.1_wp, -0.1_wp]; v(:, 1) = [0.3_wp, 0.2_wp]
        call new(name, m, 2, 1, s, err)
        call s%run(m, q, v, h, nint(10.0_wp / h, ik), st)
        call check(err, st == 0, name//': HH run failed')
        z = [q(:, 1), v(:, 1)]
    end subroutine hh_run

    subroutine t_order_hh(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        real(wp), parameter :: h(4) = [0.2_wp, 0.1_wp, 0.05_wp, 0.025_wp]
        real(wp) :: z(4, 4), d(3), p(2), expect
        character(len=160) :: line
        integer :: k, j
        names = fsym_method_names()
        do k = 1, size(names)
            do j = 1, 4
                call hh_run(trim(names(k)), h(j), z(:, j), err)
            end do
            do j = 1, 3
                d(j) = maxval(abs(z(:, j) - z(:, j + 1)))
            end do
            p = fsym_observed_orders(h(1:3), d)
            expect = merge(2.0_wp, 4.0_wp, names(k) == 'T2')
            write (line, '(a,a10,a,3es10.2,a,2f7.3)') 'order HH     ', trim(names(k)), &
                '  diff', d, '  p', p
            call note(trim(line))
            call check(err, abs(p(2) - expect) < 0.2_wp, trim(line))
        end do
    end subroutine t_order_hh

    real(wp) function defect_of(name, model, q, v, h, err) result(defect)
        character(len=*), intent(in) :: name
        class(force_model_t), intent(inout) :: model
        real(wp), intent(in) :: q(:, :), v(:, :), h
        character(len=:), allocatable, intent(inout) :: err
        class(stepper_t), allocatable :: s
        real(wp) :: jac(2 * size(q), 2 * size(q))
        integer :: st
        character(len=256) :: msg
        call new(name, model, size(q, 1), size(q, 2), s, err)
        call fsym_step_jacobian(s, model, q, v, h, jac, st, msg)
        call check(err, st == 0, 'jacobian: '//trim(msg))
        defect = fsym_symplectic_defect(jac)
    end function defect_of

    subroutine t_symplectic(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(henon_heiles_model_t) :: hh
        type(kepler_model_t) :: kep
        real(wp) :: dh, dk, q(2, 1), v(2, 1), p, q0(2), v0(2)
        character(len=160) :: line
        logical :: exact_on_kepler, exact_on_hh
        type(scheme_t) :: s
        integer :: k
        names = fsym_method_names()
        call kepler_paper_orbit(q0, v0, p)
        ! near the pericentre, where the force varies fastest
        call kepler_exact(q0, v0, 0.48_wp * p, q(:, 1), v(:, 1), k)
        do k = 1, size(names)
            ! a point where the Henon-Heiles torque x^3 - 3xy^2 is not small
            dh = defect_of(trim(names(k)), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                           reshape([0.0_wp, 0.2_wp], [2, 1]), 0.2_wp, err)
            dk = defect_of(trim(names(k)), kep, q, v, p / 200.0_wp, err)
            write (line, '(a,a10,a,es10.2,a,es10.2)') 'symplectic defect ', trim(names(k)), &
                '  HH', dh, '  Kepler', dk
            call note(trim(line))
            if (names(k) == 'RKN') then
                exact_on_hh = .false.; exact_on_kepler = .false.
            else
                call fsym_scheme_by_name(trim(names(k)), s)
                exact_on_hh = s%symplectic
                exact_on_kepler = .true.          ! extrapolated forms are exact for central forces
            end if
            if (exact_on_hh) then
                call check(err, dh < 1e-11_wp, trim(line)//' (HH should be symplectic)')
            else
                call check(err, dh > 1e-10_wp, trim(line)//' (HH should not be exactly symplectic)')
            end if
            if (exact_on_kepler) then
                call check(err, dk < 1e-11_wp, trim(line)//' (Kepler should be symplectic)')
            else
                call check(err, dk > 1e-9_wp, trim(line)//' (RKN should not be symplectic)')
            end if
        end do
    end subroutine t_symplectic

    subroutine t_extrap_defect(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=6), parameter :: names(*) = [character(len=6) :: 'A''', 'C''', 'A5''', 'A6''']
        type(henon_heiles_model_t) :: hh
        real(wp) :: d1, d2, p
        character(len=120) :: line
        integer :: k
        do k = 1, size(names)
            d1 = defect_of(trim(names(k)), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                           reshape([0.0_wp, 0.2_wp], [2, 1]), 0.2_wp, err)
            d2 = defect_of(trim(names(k)), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                           reshape([0.0_wp, 0.2_wp], [2, 1]), 0.1_wp, err)
            p = log(d1 / d2) / log(2.0_wp)
            write (line, '(a,a6,a,2es10.2,a,f6.2)') 'extrapolated defect ', names(k), &
                ' h=0.2,0.1', d1, d2, '  p', p
            call note(trim(line))
            call check(err, abs(p - 5.0_wp) < 0.5_wp, trim(line))
        end do
    end subroutine t_extrap_defect

    subroutine t_reversible(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), p, defect
        integer :: k, st
        names = fsym_catalogue()
        q(:, 1) = [0.8_wp, 0.3_wp]; v(:, 1) = [-0.2_wp, 1.1_wp]
        p = 0.05_wp
        do k = 1, size(names)
            call new(trim(names(k)), kep, 2, 1, s, err)
            call fsym_reversibility_defect(s, kep, q, v, p, defect, st)
            call check(err, defect < 1e-14_wp, trim(names(k))//' not reversible')
        end do
    end subroutine t_reversible

    subroutine t_counts(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), p
        integer(ik) :: f1, g1
        integer :: k, st
        type(scheme_t) :: sc
        names = fsym_method_names()
        do k = 1, size(names)
            call kepler_paper_orbit(q(:, 1), v(:, 1), p)
            call new(trim(names(k)), kep, 2, 1, s, err)
            call s%step(kep, q, v, p / 1000, st)
            f1 = s%force_evaluations(); g1 = s%gradient_evaluations()
            call s%run(kep, q, v, p / 1000, 100_ik, st)
            call check(err, s%force_evaluations() - f1 == 100 * s%forces_per_step(), &
                       trim(names(k))//': measured forces per step differ from the table')
            call check(err, s%gradient_evaluations() - g1 == 100 * s%gradients_per_step(), &
                       trim(names(k))//': measured gradients per step differ')
            if (names(k) == 'RKN') then
                call check(err, .not. s%is_splitting() .and. s%forces_per_step() == 3, 'RKN')
            else
                call fsym_scheme_by_name(trim(names(k)), sc)
                call check(err, s%is_splitting() .and. (s%is_forward() .eqv. sc%forward), &
                           trim(names(k))//' flags')
            end if
        end do
    end subroutine t_counts

    subroutine t_no_gradient_work(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1)
        integer :: st
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call it%init_by_name('BM', kep, 2, 1, st)
        call it%run(kep, q, v, 0.01_wp, 50_ik, st)
        call check(err, it%gradient_evaluations() == 0, 'BM evaluated gradients')
        call check(err, it%work_size() == 4 * 2, 'BM should hold 4 slots of work, no gradient slot')
        call it%init_by_name('A''', kep, 2, 1, st)
        call it%run(kep, q, v, 0.01_wp, 50_ik, st)
        call check(err, it%gradient_evaluations() == 0, 'A'' evaluated gradients')
    end subroutine t_no_gradient_work

    subroutine t_fsal_cache(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: a, b
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1), qb(2, 1), vb(2, 1)
        integer(ik) :: f0
        integer :: st
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call a%init_by_name('M2(-0.5)', kep, 2, 1, st)
        call a%step(kep, q, v, 0.01_wp, st)
        f0 = a%force_evaluations()
        call a%step(kep, q, v, 0.01_wp, st)
        call check(err, a%force_evaluations() - f0 == 4, 'FSAL: 4 forces in the second step')
        ! move q behind the integrator's back: the cached force must not be used
        q(1, 1) = q(1, 1) + 1e-3_wp
        qb = q; vb = v
        f0 = a%force_evaluations()
        call a%step(kep, q, v, 0.01_wp, st)
        call check(err, a%force_evaluations() - f0 == 5, 'changed q: 5 forces')
        call b%init_by_name('M2(-0.5)', kep, 2, 1, st)
        call b%step(kep, qb, vb, 0.01_wp, st)
        call check(err, all(q == qb) .and. all(v == vb), 'changed q: same as a fresh integrator')
    end subroutine t_fsal_cache

    subroutine t_particles(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: all3, one
        type(kepler_model_t) :: kep
        real(wp) :: q(3, 3), v(3, 3), q1(3, 1), v1(3, 1), q0(3, 3), v0(3, 3)
        integer :: j, st
        q0 = reshape([1.0_wp, 0.0_wp, 0.1_wp, 0.0_wp, 2.0_wp, 0.0_wp, -1.5_wp, 0.2_wp, 0.3_wp], &
                     [3, 3])
        v0 = reshape([0.0_wp, 1.0_wp, 0.0_wp, -0.6_wp, 0.0_wp, 0.1_wp, 0.1_wp, -0.7_wp, 0.0_wp], &
                     [3, 3])
        q = q0; v = v0
        call all3%init_by_name('C', kep, 3, 3, st)
        call all3%run(kep, q, v, 0.01_wp, 300_ik, st)
        do j = 1, 3
            q1(:, 1) = q0(:, j); v1(:, 1) = v0(:, j)
            call one%init_by_name('C', kep, 3, 1, st)
            call one%run(kep, q1, v1, 0.01_wp, 300_ik, st)
            call check(err, all(q1(:, 1) == q(:, j)) .and. all(v1(:, 1) == v(:, j)), &
                       'body run alone differs')
        end do
        call check(err, abs(kepler_energy(q(:, 1), v(:, 1)) - kepler_energy(q0(:, 1), v0(:, 1))) &
                   < 1e-8_wp, '3D energy')
    end subroutine t_particles

    !> Max |E - E0| of the oscillator over 1e6 steps of h = 1e-4 with A.
    real(wp) function osc_energy_drift(comp, err) result(de)
        logical, intent(in) :: comp
        character(len=:), allocatable, intent(inout) :: err
        type(integrator_t) :: it
        type(oscillator_model_t) :: osc
        real(wp) :: q(2, 1), v(2, 1), e0
        integer :: k, st
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        e0 = 0.5_wp * (sum(q**2) + sum(v**2))
        call it%init_by_name('A', osc, 2, 1, st, compensated=comp)
        de = 0.0_wp
        do k = 1, 100
            call it%run(osc, q, v, 1.0e-4_wp, 10000_ik, st)
            de = max(de, abs(0.5_wp * (sum(q**2) + sum(v**2)) - e0))
        end do
        call check(err, st == 0, 'oscillator run')
    end function osc_energy_drift

    subroutine t_compensated(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: plain, comp
        character(len=120) :: line
        plain = osc_energy_drift(.false., err)
        comp = osc_energy_drift(.true., err)
        write (line, '(a,es10.2,a,es10.2)') 'oscillator 1e6 steps max|dE|: plain', plain, &
            '  compensated', comp
        call note(trim(line))
        call check(err, comp < plain / 10.0_wp, trim(line))
    end subroutine t_compensated

    subroutine t_recorder(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: a, b
        type(kepler_model_t) :: kep
        type(trace_recorder_t) :: rec
        real(wp) :: q(2, 1), v(2, 1), qb(2, 1), vb(2, 1)
        integer :: st
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        qb = q; vb = v
        call rec%init(2, 1, 100)
        call a%init_by_name('A''', kep, 2, 1, st)
        call b%init_by_name('A''', kep, 2, 1, st)
        call a%run(kep, q, v, 0.1_wp, 5_ik, st, recorder=rec)
        call b%run(kep, qb, vb, 0.1_wp, 5_ik, st)
        call check(err, all(q == qb) .and. all(v == vb), 'recording changed the result')
        call check(err, rec%count == a%force_evaluations(), 'one point per evaluation')
        call check(err, count(rec%kind(1:rec%count) == EVAL_EXTRAPOLATED) == 5, &
                   'one extrapolated point per step')
        call check(err, rec%step(rec%count) == 5, 'step numbers recorded')
    end subroutine t_recorder

    subroutine t_clock(err)
        character(len=:), allocatable, intent(out) :: err
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1)
        integer :: st
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call it%init_by_name('FR', kep, 2, 1, st, t0=3.0_wp)
        call it%run(kep, q, v, 0.1_wp, 1000_ik, st)
        call check(err, it%time() == 3.0_wp + 1000 * 0.1_wp, 'time = t0 + n h exactly')
        call check(err, it%steps() == 1000, 'step count')
    end subroutine t_clock

end module test_integrator
