!> Planetary benchmark: the outer solar system (Sun + Jupiter, Saturn, Uranus, Neptune, Pluto;
!> data file of scripts/planets.sh) over `years` years at h = P_Jupiter/`div`, with every
!> method of the catalogue run with Kepler drifts (the Wisdom-Holman splitting, Jacobi
!> coordinates; `[dh]`: democratic heliocentric) and the best kinetic + potential method
!> (Chin's C on the Newtonian N-body model, `C(T+V)`), and J. Laskar and P. Robutel's two-force
!> SABA2, SBAB2 (Celest. Mech. Dyn. Astron. 80 (2001) 39). One line per method:
!> Then the processed methods of `fsym_processed` (WH, WHK-M, WHK-L kernels with correctors, e.g.
!> `WHK-L+C17`), maxdE from the corrected output after every step, in the same line form.
!>
!>     planets METHOD h=P/40 maxdE=X evals=E ns_per_step=T
!>
!> maxdE: max |E(t) - E(0)| / |E(0)| over every step; evals: force evaluations per step with
!> the first-same-as-last reuse, a gradient counted as one; ns_per_step: wall time per step,
!> the minimum over `reps` repetitions taken in turn (method after method, then again), with
!> the spread (max/min) on a comment line.
!>
!> Usage: fsym-planets-bench data-file [years [div [reps [mscale]]]]
!>        (mscale: every planet's mass times mscale, the Sun's unchanged; 1 by default; the
!>        error linear in the mass ratio eps then scales as mscale, the eps^2 part as mscale^2,
!>        which `bash scripts/planets.sh --eps-split` uses to separate them)
!>        fsym-planets-bench --orders   (fitted eps and h exponents of every table, lines
!>                                       `orders METHOD order=N p=P q=Q`, as test_planets;
!>                                       `# quadrature` lines: the kicks' quadrature order
!>                                       and moment error; `# scan SRKN6b` lines)
program fsym_planets_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_solar_data, only: solar_data_t, read_solar_data
    use fsym_exit, only: fsym_exit_failure
    use fsym_planets_fit, only: evaluations_per_step, fit_eps_exponents, kick_quadrature
    implicit none
    character(len=512) :: path, arg
    character(len=256) :: msg
    type(solar_data_t) :: dat
    type(planets_model_t) :: jac, dem
    type(nbody_model_t) :: nb
    type(integrator_t) :: integ, pit
    character(len=24), allocatable :: names(:)
    character(len=24) :: label
    type(scheme_t), allocatable :: schemes(:)
    integer, allocatable :: coords(:)
    real(wp), allocatable :: m(:), xb(:, :), vb(:, :), q0j(:, :), v0j(:, :), q0d(:, :), &
                             v0d(:, :), q(:, :), v(:, :), &
                             qb(:, :), ub(:, :), best(:), worst(:), maxde(:)
    integer, allocatable :: evals(:)
    real(wp) :: years, div, pj, h, xcm(3), vcm(3), e0, aj, rj, vj2, mu, mscale
    integer(int64) :: nsteps, k, t0, t1, rate
    integer :: reps, nmeth, i, j, st, isun, n, nc, rep
    call get_command_argument(1, path)
    if (path == '--orders') then
        call print_orders()
        stop
    end if
    years = 2000.0_wp; div = 40.0_wp; reps = 5; mscale = 1.0_wp
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg); read (arg, *, iostat=st) years
        if (st /= 0) call fail('cannot read argument 2: '//trim(arg))
    end if
    if (command_argument_count() >= 3) then
        call get_command_argument(3, arg); read (arg, *, iostat=st) div
        if (st /= 0) call fail('cannot read argument 3: '//trim(arg))
    end if
    if (command_argument_count() >= 4) then
        call get_command_argument(4, arg); read (arg, *, iostat=st) reps
        if (st /= 0) call fail('cannot read argument 4: '//trim(arg))
    end if
    if (command_argument_count() >= 5) then
        call get_command_argument(5, arg); read (arg, *, iostat=st) mscale
        if (st /= 0) call fail('cannot read argument 5: '//trim(arg))
        if (.not. (mscale > 0.0_wp)) call fail('mscale must be positive')
    end if
    call read_solar_data(trim(path), dat, st, msg)
    if (st /= 0) call fail(msg)
    ! the Sun is the centre; the others in the file's order
    isun = 0
    do i = 1, dat%n
        if (trim(dat%name(i)) == 'Sun') isun = i
    end do
    if (isun == 0) call fail('no body named Sun in '//trim(path))
    n = dat%n - 1
    allocate (m(n), xb(3, 0:n), vb(3, 0:n))
    xb(:, 0) = dat%q0(:, isun); vb(:, 0) = dat%v0(:, isun)
    j = 0
    do i = 1, dat%n
        if (i == isun) cycle
        j = j + 1
        m(j) = mscale * dat%m(i)
        xb(:, j) = dat%q0(:, i); vb(:, j) = dat%v0(:, i)
    end do
    ! P_Jupiter from its heliocentric two-body energy (the first body)
    mu = dat%g * (dat%m(isun) + m(1))
    rj = norm2(xb(:, 1) - xb(:, 0)); vj2 = sum((vb(:, 1) - vb(:, 0))**2)
    aj = 1.0_wp / (2.0_wp / rj - vj2 / mu)
    pj = 2.0_wp * FSYM_PI * sqrt(aj**3 / mu)
    h = pj / div
    nsteps = nint(years * 365.25_wp / h, int64)
    call jac%init(dat%m(isun), m, dat%g, PLANETS_JACOBI, st, msg)
    if (st /= 0) call fail(msg)
    call dem%init(dat%m(isun), m, dat%g, PLANETS_DEMOCRATIC, st, msg)
    if (st /= 0) call fail(msg)
    allocate (q0j(3, n), v0j(3, n), q0d(3, n), v0d(3, n), q(3, n), v(3, n))
    call jac%to_state(xb, vb, q0j, v0j, xcm, vcm)
    call dem%to_state(xb, vb, q0d, v0d, xcm, vcm)
    ! the methods: the catalogue with Kepler drifts (Jacobi), T2 and C' also democratic, and
    ! Laskar & Robutel's SABA2, SBAB2
    nc = size(fsym_catalogue())
    nmeth = nc + 4
    allocate (names(nmeth), schemes(nmeth), coords(nmeth), best(nmeth + 1), &
              worst(nmeth + 1), maxde(nmeth + 1), evals(nmeth + 1))
    names(1:nc) = fsym_catalogue()
    coords(1:nc) = PLANETS_JACOBI
    names(nc + 1) = 'T2'; coords(nc + 1) = PLANETS_DEMOCRATIC
    names(nc + 2) = 'C'''; coords(nc + 2) = PLANETS_DEMOCRATIC
    ! Laskar & Robutel's two-force methods (eps h^4 + eps^2 h^2), Jacobi
    names(nc + 3) = 'SABA2'; coords(nc + 3) = PLANETS_JACOBI
    names(nc + 4) = 'SBAB2'; coords(nc + 4) = PLANETS_JACOBI
    do i = 1, nmeth
        call fsym_scheme_by_name(trim(names(i)), schemes(i), st, msg)
        if (st /= 0) call fail(msg)
        evals(i) = evaluations_per_step(schemes(i))
    end do
    ! the kinetic + potential comparator on barycentric coordinates
    allocate (qb(3, 0:n), ub(3, 0:n))
    call nb%init([dat%m(isun), m], dat%g, 0.0_wp, st, msg)
    if (st /= 0) call fail(msg)
    call integ%init_by_name('C', nb, 3, n + 1, st, msg)
    if (st /= 0) call fail(msg)
    evals(nmeth + 1) = evals_tv()

    ! accuracy: energy after every step
    do i = 1, nmeth
        call start(i)
        e0 = model_energy(i)
        maxde(i) = 0.0_wp
        call init_method(i)
        do k = 1, nsteps
            if (coords(i) == PLANETS_JACOBI) then
                call pit%step(jac, q, v, h, st)
            else
                call pit%step(dem, q, v, h, st)
            end if
            if (st /= 0) call fail('method '//trim(names(i))//' failed')
            maxde(i) = max(maxde(i), abs((model_energy(i) - e0) / e0))
        end do
    end do
    call start_tv()
    e0 = nb%energy(qb, ub)
    maxde(nmeth + 1) = 0.0_wp
    do k = 1, nsteps
        call integ%step(nb, qb, ub, h, st, msg)
        if (st /= 0) call fail(msg)
        maxde(nmeth + 1) = max(maxde(nmeth + 1), abs((nb%energy(qb, ub) - e0) / e0))
    end do

    ! speed: whole runs, contenders in turn, min and max over the repetitions
    best = huge(1.0_wp); worst = 0.0_wp
    call system_clock(count_rate=rate)
    do rep = 1, reps
        do i = 1, nmeth + 1
            if (i <= nmeth) then
                call start(i)
                call init_method(i)
            else
                call start_tv()
            end if
            call system_clock(t0)
            if (i > nmeth) then
                call integ%run(nb, qb, ub, h, nsteps, st, msg)
            else if (coords(i) == PLANETS_JACOBI) then
                call pit%run(jac, q, v, h, nsteps, st)
            else
                call pit%run(dem, q, v, h, nsteps, st)
            end if
            call system_clock(t1)
            if (st /= 0) call fail('a timed run failed')
            best(i) = min(best(i), real(t1 - t0, wp) / real(rate, wp) / real(nsteps, wp))
            worst(i) = max(worst(i), real(t1 - t0, wp) / real(rate, wp) / real(nsteps, wp))
        end do
    end do

    write (output_unit, '(a,f8.2,a,f9.3,a,i0,a,f7.1,a,i0,a)') '# outer solar system: P_J = ', &
        pj, ' d, h = ', h, ' d, ', nsteps, ' steps (', years, ' years), ', reps, &
        ' repetitions in turn'
    do i = 1, nmeth + 1
        if (i <= nmeth) then
            label = names(i)
            if (coords(i) == PLANETS_DEMOCRATIC) label = trim(names(i))//'[dh]'
        else
            label = 'C(T+V)'
        end if
        write (output_unit, '(a,a,a,i0,a,es9.2,a,i0,a,f0.1,a,f0.2)') 'planets ', trim(label), &
            ' h=P/', nint(div), ' maxdE=', maxde(i), ' evals=', evals(i), ' ns_per_step=', &
            1.0e9_wp * best(i)
    end do
    write (output_unit, '(a,f0.2)') '# largest spread of the timings (max/min over '// &
        'repetitions): ', maxval(worst / best)
    call processed_lines()

contains

    !> The processed methods (fsym_processed, Jacobi): the kick-drift-kick kernels WH, WHK-M,
    !> WHK-L with and without the corrector of order 17; maxdE of the corrected output after
    !> every step (output on a copy), the timing of the bare runs (output does not change
    !> them), contenders in turn.
    subroutine processed_lines()
        integer, parameter :: np = 6
        character(len=12), parameter :: pl(np) = [character(len=12) :: 'WH', 'WH+C3', &
            'WH+C17', 'WHK-M+C17', 'WHK-L+C17', 'T2+C17']
        type(processed_t) :: pm(np)
        type(planets_model_t) :: je
        real(wp) :: pbest(np), pworst(np), pmax(np), qo(3, n), vo(3, n)
        integer :: ip
        ! Jacobi with the Kepler masses eta_k (as the race); the Jacobi arrays are the same
        call je%init(dat%m(isun), m, dat%g, PLANETS_JACOBI, st, msg, &
                     kepler_masses=PLANETS_KEPLER_ETA)
        if (st /= 0) call fail(msg)
        do ip = 1, np
            call pm(ip)%init(trim(pl(ip)), je, q0j, v0j, h, st, msg)
            if (st /= 0) call fail(msg)
            call pm(ip)%output(je, qo, vo, st, msg)
            e0 = je%energy(qo, vo)
            pmax(ip) = 0.0_wp
            do k = 1, nsteps
                call pm(ip)%run(je, 1_int64, st, msg)
                if (st /= 0) call fail(msg)
                call pm(ip)%output(je, qo, vo, st, msg)
                if (st /= 0) call fail(msg)
                pmax(ip) = max(pmax(ip), abs((je%energy(qo, vo) - e0) / e0))
            end do
        end do
        pbest = huge(1.0_wp); pworst = 0.0_wp
        do rep = 1, reps
            do ip = 1, np
                call pm(ip)%init(trim(pl(ip)), je, q0j, v0j, h, st, msg)
                if (st /= 0) call fail(msg)
                call system_clock(t0)
                call pm(ip)%run(je, nsteps, st, msg)
                call system_clock(t1)
                if (st /= 0) call fail('a timed run failed')
                pbest(ip) = min(pbest(ip), real(t1 - t0, wp) / real(rate, wp) / real(nsteps, wp))
                pworst(ip) = max(pworst(ip), real(t1 - t0, wp) / real(rate, wp) / &
                                 real(nsteps, wp))
            end do
        end do
        write (output_unit, '(a)') '# processed (kick-drift-kick kernels, Jacobi, Kepler '// &
            'masses eta_k; maxdE of the corrected output after every step):'
        do ip = 1, np
            write (output_unit, '(a,a,a,i0,a,es9.2,a,i0,a,f0.1)') 'planets ', trim(pl(ip)), &
                ' h=P/', nint(div), ' maxdE=', pmax(ip), ' evals=', pm(ip)%evaluations(), &
                ' ns_per_step=', 1.0e9_wp * pbest(ip)
        end do
        write (output_unit, '(a,f0.2)') '# largest spread of these timings: ', &
            maxval(pworst / pbest)
    end subroutine processed_lines

    !> The fitted exponents of every table (see `fit_eps_exponents`).
    subroutine print_orders()
        integer, parameter :: scan_nper(5) = [12, 16, 20, 30, 40]
        real(wp), parameter :: scan_eps(3) = [1.0e-3_wp, 1.0e-2_wp, 3.0e-2_wp]
        type(scheme_t) :: s, sref
        real(wp) :: p, pq
        integer :: i, k, st
        names = fsym_catalogue()
        call fsym_scheme_by_name('SRKN6b', sref)
        do i = 1, size(names)
            call fsym_scheme_by_name(trim(names(i)), s)
            call fit_eps_exponents(s, sref, p, pq, st)
            if (st /= 0) call fail('a run of '//trim(names(i))//' failed')
            write (output_unit, '(a,a,a,i0,a,f6.3,a,f6.3)') 'orders ', trim(names(i)), &
                ' order=', s%order, ' p=', p, ' q=', pq
        end do
        ! the eps-linear error is the error of the kicks' quadrature along the Kepler flow
        do i = 1, size(names)
            call fsym_scheme_by_name(trim(names(i)), s)
            call print_quadrature(s)
        end do
        ! SRKN6b's tiny quadrature error: its fit over steps and mass ratios
        call fsym_scheme_by_name('SRKN6b', s)
        do i = 1, size(scan_nper)
            do k = 1, size(scan_eps)
                call fit_eps_exponents(s, sref, p, pq, st, nper=scan_nper(i), eps=scan_eps(k))
                if (st /= 0) call fail('a run of SRKN6b failed')
                write (output_unit, '(a,i0,a,es8.1,a,f7.3,a,f7.3)') '# scan SRKN6b nper=', &
                    scan_nper(i), ' eps=', scan_eps(k), ' p=', p, ' q=', pq
            end do
        end do
    end subroutine print_orders

    !> One `# quadrature` line: the order and moment error of a table's kick quadrature.
    subroutine print_quadrature(s)
        type(scheme_t), intent(in) :: s
        real(wp) :: err
        integer :: kk
        call kick_quadrature(s, kk, err)
        write (output_unit, '(a,a,a,i0,a,es10.3)') '# quadrature ', trim(s%name), ' order=', kk, &
            ' moment_error=', err
    end subroutine print_quadrature

    !> The integrator of method i, set up afresh (the one kernel with the model's drift).
    subroutine init_method(i)
        integer, intent(in) :: i
        if (coords(i) == PLANETS_JACOBI) then
            call pit%init(schemes(i), jac, 3, size(q, 2), st, msg)
        else
            call pit%init(schemes(i), dem, 3, size(q, 2), st, msg)
        end if
        if (st /= 0) call fail(msg)
    end subroutine init_method

    !> Set the state of method i to the start.
    subroutine start(i)
        integer, intent(in) :: i
        if (coords(i) == PLANETS_JACOBI) then
            q = q0j; v = v0j
        else
            q = q0d; v = v0d
        end if
    end subroutine start

    !> Set the barycentric state of the comparator to the start.
    subroutine start_tv()
        real(wp) :: z(3)
        z = 0.0_wp
        call jac%from_state(q0j, v0j, z, z, qb, ub)
        call integ%reset_cache()
    end subroutine start_tv

    !> Evaluations per step of the comparator's scheme.
    integer function evals_tv()
        type(scheme_t) :: s
        s = integ%scheme()
        evals_tv = s%nforce + s%ngrad
    end function evals_tv

    real(wp) function model_energy(i)
        integer, intent(in) :: i
        if (coords(i) == PLANETS_JACOBI) then
            model_energy = jac%energy(q, v)
        else
            model_energy = dem%energy(q, v)
        end if
    end function model_energy

    subroutine fail(text)
        character(len=*), intent(in) :: text
        call fsym_exit_failure('fsym-planets-bench', text)
    end subroutine fail

end program fsym_planets_bench
