!> Work-precision study: every method of the library (the catalogue and RKN) on three Kepler
!> orbits, error against run time and against evaluations. Each method's step sizes extend
!> (coarser and finer, by the same geometric factor) until every target error of its orbit is
!> bracketed, so the time to each target is interpolated between two runs, never bounded.
!> Timings are the minimum over interleaved repetitions (every run of an orbit once, then
!> again, ...), with the median and maximum kept as the spread, on two clocks: wall time and
!> the CPU time of the thread (steadier on a shared machine); every sample is kept, so the
!> report can compare the odd and the even rounds (two independent repetitions of the
!> study). The cost of a gradient evaluation relative to a force evaluation is measured in
!> repeated pairs; its spread over the pairs is kept. Writes the HDF5 file read by
!> scripts/report_workprec.py (which renders doc/work-precision.md and the figures) and the
!> CSV of every run (doc/work-precision.csv). Both outputs are checked writable before the
!> work and written through temporary names.
!>
!>     fsym-workprec [--h5 FILE] [--csv FILE] [--hardware TEXT] [--flags TEXT]
!>                   [--nsweep N] [--reps R] [--nmax N]
!>
!> Orbits: 1. the paper's e = 0.9 orbit (d = 2, 10 periods); 2. the e = 0.6 orbit of Hairer,
!> Lubich and Wanner (d = 2, 200 periods); 3. the same e = 0.6 orbit tilted out of the plane
!> (d = 3, 50 periods).
program fsym_workprec
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use fsym
    use fsym_timing, only: seconds_since, median, thread_cpu_seconds
    use fsym_h5, only: h5_file_t, fsym_check_writable, fsym_open_text, fsym_commit_text, &
                       fsym_h5_safe_name, fsym_h5md_header
    implicit none

    integer, parameter :: NORBIT = 3, MAXPT = 80
    real(wp), parameter :: NMIN = 100.0_wp            ! base grid: steps per period, coarsest
    real(wp), parameter :: NFLOOR = 4.0_wp            ! never coarser than P/4
    real(wp), parameter :: NCAP = 4.0e6_wp            ! never finer than P/4e6
    real(wp), parameter :: TMIN_RUN = 0.004_wp        ! a timed sample lasts at least this (s)
    integer, parameter :: DIMS(NORBIT) = [2, 2, 3]
    integer, parameter :: PERIODS(NORBIT) = [10, 200, 50]
    character(len=*), parameter :: ORBIT_NAME(NORBIT) = [character(len=40) :: &
        'e = 0.9 (paper), d = 2, 10 periods', 'e = 0.6, d = 2, 200 periods', &
        'e = 0.6 tilted, d = 3, 50 periods']
    character(len=*), parameter :: GROUP(NORBIT) = [character(len=8) :: 'e0.9', 'e0.6', &
                                                    'e0.6_3d']
    real(wp), parameter :: ETARGET(2) = [1.0e-4_wp, 1.0e-8_wp]   ! max |dE/E| targets
    real(wp), parameter :: PTARGET = 1.0e-6_wp                   ! |precession| target, orbit 1

    character(len=FSYM_NAME_LEN), allocatable :: names(:)
    character(len=512) :: h5_path, csv_path, hardware, flags, arg, msg
    integer, parameter :: NGPAIR = 9                  ! force/gradient timing pairs
    real(wp) :: nmax = 20000.0_wp, ratio, gcost, gpair(NGPAIR), t_all
    integer :: nsweep = 12, nreps = 6, nm, io, im, ie, st, i, rep
    integer, allocatable :: npt(:, :), ordm(:), inner(:, :, :)
    real(wp), allocatable :: nper(:, :, :), tmin(:, :, :), tmed(:, :, :), tmax(:, :, :)
    real(wp), allocatable :: de(:, :, :), prec(:, :, :), phase(:, :, :), nfe(:, :, :)
    real(wp), allocatable :: nge(:, :, :), samples(:, :, :, :), csamples(:, :, :, :)
    real(wp), allocatable :: cmin(:, :, :), cmed(:, :, :), cmax(:, :, :)
    logical, allocatable :: fwd(:)
    integer(int64) :: t0

    h5_path = 'out/work-precision.h5'
    csv_path = 'doc/work-precision.csv'
    hardware = 'unknown'; flags = 'unknown'
    i = 0
    do while (i < command_argument_count())
        i = i + 1
        call get_command_argument(i, arg)
        select case (trim(arg))
        case ('--h5'); call next_value(h5_path)
        case ('--csv'); call next_value(csv_path)
        case ('--hardware'); call next_value(hardware)
        case ('--flags'); call next_value(flags)
        case ('--nsweep'); call next_value(arg); read (arg, *, iostat=st) nsweep; call ok_read()
        case ('--reps'); call next_value(arg); read (arg, *, iostat=st) nreps; call ok_read()
        case ('--nmax'); call next_value(arg); read (arg, *, iostat=st) nmax; call ok_read()
        case default; call die('unknown argument "'//trim(arg)//'"')
        end select
    end do
    nsweep = max(2, nsweep); nreps = max(1, nreps)
    call fsym_check_writable(trim(h5_path), st, msg)     ! before the work, not after
    if (st /= FSYM_SUCCESS) call die(msg)
    call fsym_check_writable(trim(csv_path), st, msg)
    if (st /= FSYM_SUCCESS) call die(msg)
    call system_clock(t0)

    names = fsym_method_names()
    nm = size(names)
    allocate (npt(nm, NORBIT), inner(MAXPT, nm, NORBIT), ordm(nm), fwd(nm))
    allocate (nper(MAXPT, nm, NORBIT), tmin(MAXPT, nm, NORBIT), samples(nreps, MAXPT, nm, NORBIT))
    allocate (tmed, tmax, de, prec, phase, nfe, nge, cmin, cmed, cmax, mold=nper)
    allocate (csamples, mold=samples)
    tmin = ieee_nan(); tmed = tmin; tmax = tmin; de = tmin; prec = tmin; phase = tmin
    cmin = tmin; cmed = tmin; cmax = tmin
    nfe = 0.0_wp; nge = 0.0_wp; inner = 1; samples = ieee_nan(); csamples = ieee_nan()
    call method_orders()
    call gradient_cost(gcost, gpair)
    write (output_unit, '(a,f0.3,a,f0.3,a,f0.3,a)') 'gradient cost / force cost = ', gcost, &
        ' (pairs: ', minval(gpair), ' .. ', maxval(gpair), ')'
    ratio = (nmax / NMIN)**(1.0_wp / real(nsweep - 1, wp))

    ! 1. the grids and the untimed diagnostics of every run
    do io = 1, NORBIT
        do im = 1, nm
            call sweep(io, im)
        end do
        write (output_unit, '(a,f0.1,a)') 'orbit '//trim(ORBIT_NAME(io))//': grids done (', &
            seconds_since(t0), ' s)'
        flush (output_unit)
    end do
    ! 2. timings: every run of an orbit once per round, nreps rounds
    do io = 1, NORBIT
        do rep = 1, nreps
            do im = 1, nm
                do ie = 1, npt(im, io)
                    call timed_run(io, im, ie, samples(rep, ie, im, io), &
                                   csamples(rep, ie, im, io))
                end do
            end do
        end do
        do im = 1, nm
            do ie = 1, npt(im, io)
                tmin(ie, im, io) = minval(samples(:, ie, im, io))
                tmed(ie, im, io) = median(samples(:, ie, im, io))
                tmax(ie, im, io) = maxval(samples(:, ie, im, io))
                cmin(ie, im, io) = minval(csamples(:, ie, im, io))
                cmed(ie, im, io) = median(csamples(:, ie, im, io))
                cmax(ie, im, io) = maxval(csamples(:, ie, im, io))
            end do
        end do
        write (output_unit, '(a,f0.1,a)') 'orbit '//trim(ORBIT_NAME(io))//': timings done (', &
            seconds_since(t0), ' s)'
        flush (output_unit)
    end do
    t_all = seconds_since(t0)
    call write_csv()
    call write_h5()
    write (output_unit, '(a)') 'wrote '//trim(h5_path)//' and '//trim(csv_path)

contains

    subroutine die(text)
        character(len=*), intent(in) :: text
        write (error_unit, '(a)') 'fsym-workprec: '//trim(text)
        error stop 1
    end subroutine die

    subroutine next_value(out)
        character(len=*), intent(out) :: out
        if (i >= command_argument_count()) call die(trim(arg)//' needs a value')
        i = i + 1
        call get_command_argument(i, out)
    end subroutine next_value

    subroutine ok_read()
        if (st /= 0) call die('not a number after '//trim(arg))
    end subroutine ok_read

    real(wp) function ieee_nan()
        ieee_nan = ieee_value(1.0_wp, ieee_quiet_nan)
    end function ieee_nan

    !> Initial state (first `DIMS(io)` entries used), period of orbit io.
    subroutine orbit(io, q, v, period)
        integer, intent(in) :: io
        real(wp), intent(out) :: q(3), v(3), period
        real(wp) :: q2(2), v2(2)
        q = 0.0_wp; v = 0.0_wp
        select case (io)
        case (1)
            call kepler_paper_orbit(q2, v2, period)
            q(1:2) = q2; v(1:2) = v2
        case (2)
            call kepler_elliptic_orbit(0.6_wp, q2, v2, period)
            q(1:2) = q2; v(1:2) = v2
        case default
            ! the e = 0.6 orbit rotated by 30 degrees about x, then 20 degrees about z
            call kepler_elliptic_orbit(0.6_wp, q2, v2, period)
            q = tilt([q2(1), q2(2), 0.0_wp]); v = tilt([v2(1), v2(2), 0.0_wp])
        end select
    end subroutine orbit

    !> Rotation by 30 degrees about x, then 20 degrees about z.
    pure function tilt(x) result(y)
        real(wp), intent(in) :: x(3)
        real(wp) :: y(3), z(3), c1, s1, c2, s2
        c1 = cos(FSYM_PI / 6.0_wp); s1 = sin(FSYM_PI / 6.0_wp)
        c2 = cos(FSYM_PI / 9.0_wp); s2 = sin(FSYM_PI / 9.0_wp)
        z = [x(1), c1 * x(2) - s1 * x(3), s1 * x(2) + c1 * x(3)]
        y = [c2 * z(1) - s2 * z(2), s2 * z(1) + c2 * z(2), z(3)]
    end function tilt

    !> True when the run's errors are above every target of orbit io (the coarse end of a
    !> bracket) or, with `below`, at or below every target (the fine end).
    logical function beyond(io, e, p, below)
        integer, intent(in) :: io
        real(wp), intent(in) :: e, p
        logical, intent(in) :: below
        if (below) then
            beyond = e <= minval(ETARGET)
            if (io == 1) beyond = beyond .and. abs(p) <= PTARGET
        else
            beyond = .not. (e <= maxval(ETARGET))           ! NaN counts as above
            if (io == 1) beyond = beyond .and. .not. (abs(p) <= PTARGET)
        end if
    end function beyond

    !> The grid of method im on orbit io: the base grid NMIN .. nmax, extended by the same
    !> factor at either end until the targets are bracketed (within NFLOOR .. NCAP).
    subroutine sweep(io, im)
        integer, intent(in) :: io, im
        real(wp) :: n(MAXPT), e, p, ph, f, g
        integer :: k, nlo, nhi
        ! base grid in the middle of the index range, extensions on either side
        nlo = MAXPT / 2 - nsweep / 2
        do k = 1, nsweep
            n(nlo + k - 1) = NMIN * ratio**(k - 1)
        end do
        nhi = nlo + nsweep - 1
        do k = nlo, nhi
            call diagnose(io, im, n(k), e, p, ph, f, g)
            call keep(io, im, k, n(k), e, p, ph, f, g)
        end do
        do while (.not. beyond(io, de(nlo, im, io), prec(nlo, im, io), .false.) &
                  .and. n(nlo) / ratio >= NFLOOR .and. nlo > 1)
            nlo = nlo - 1
            n(nlo) = n(nlo + 1) / ratio
            call diagnose(io, im, n(nlo), e, p, ph, f, g)
            call keep(io, im, nlo, n(nlo), e, p, ph, f, g)
        end do
        do while (.not. beyond(io, de(nhi, im, io), prec(nhi, im, io), .true.) &
                  .and. n(nhi) * ratio <= NCAP .and. nhi < MAXPT)
            nhi = nhi + 1
            n(nhi) = n(nhi - 1) * ratio
            call diagnose(io, im, n(nhi), e, p, ph, f, g)
            call keep(io, im, nhi, n(nhi), e, p, ph, f, g)
        end do
        ! pack to 1 .. npt
        npt(im, io) = nhi - nlo + 1
        nper(1:npt(im, io), im, io) = nper(nlo:nhi, im, io)
        de(1:npt(im, io), im, io) = de(nlo:nhi, im, io)
        prec(1:npt(im, io), im, io) = prec(nlo:nhi, im, io)
        phase(1:npt(im, io), im, io) = phase(nlo:nhi, im, io)
        nfe(1:npt(im, io), im, io) = nfe(nlo:nhi, im, io)
        nge(1:npt(im, io), im, io) = nge(nlo:nhi, im, io)
    end subroutine sweep

    !> Store the diagnostics of point j.
    subroutine keep(io, im, j, n, e, p, ph, f, g)
        integer, intent(in) :: io, im, j
        real(wp), intent(in) :: n, e, p, ph, f, g
        nper(j, im, io) = n
        de(j, im, io) = e; prec(j, im, io) = p; phase(j, im, io) = ph
        nfe(j, im, io) = f; nge(j, im, io) = g
    end subroutine keep

    !> Steps of a run at n steps per period on orbit io, and the step size.
    subroutine run_size(io, n, nsteps, h)
        integer, intent(in) :: io
        real(wp), intent(in) :: n
        integer(ik), intent(out) :: nsteps
        real(wp), intent(out) :: h
        real(wp) :: q(3), v(3), period
        call orbit(io, q, v, period)
        nsteps = max(1_ik, nint(n * PERIODS(io), ik))
        h = period * PERIODS(io) / real(nsteps, wp)
    end subroutine run_size

    !> The untimed diagnostic run: max relative energy error over every step, LRL rotation
    !> at the end (signed in the orbit's plane), phase-space error against kepler_exact.
    subroutine diagnose(io, im, n, dmax, precession, perr, nf, ng)
        integer, intent(in) :: io, im
        real(wp), intent(in) :: n
        real(wp), intent(out) :: dmax, precession, perr, nf, ng
        type(kepler_model_t) :: model
        class(stepper_t), allocatable :: s
        real(wp) :: q0(3), v0(3), period, h, e0, a0(3), a1(3), ax(3), lz(3)
        real(wp), allocatable :: q(:, :), v(:, :), qx(:), vx(:)
        integer :: d, st
        integer(ik) :: k, nsteps
        character(len=256) :: msg
        d = DIMS(io)
        call orbit(io, q0, v0, period)
        call run_size(io, n, nsteps, h)
        allocate (q(d, 1), v(d, 1), qx(d), vx(d))
        call fsym_new_stepper(trim(names(im)), model, d, 1, s, st, msg)
        if (st /= FSYM_SUCCESS) call die(msg)
        fwd(im) = s%is_forward()
        q(:, 1) = q0(1:d); v(:, 1) = v0(1:d)
        e0 = kepler_energy(q0(1:d), v0(1:d))
        dmax = 0.0_wp
        do k = 1, nsteps
            call s%step(model, q, v, h, st)
            if (st /= FSYM_SUCCESS) exit
            dmax = max(dmax, abs((kepler_energy(q(:, 1), v(:, 1)) - e0) / e0))
        end do
        nf = real(s%force_evaluations(), wp)
        ng = real(s%gradient_evaluations(), wp)
        if (st /= FSYM_SUCCESS .or. .not. (dmax <= huge(1.0_wp))) then
            dmax = ieee_nan(); precession = ieee_nan(); perr = ieee_nan()
            return
        end if
        a0 = 0.0_wp; a1 = 0.0_wp; lz = 0.0_wp
        call kepler_lrl(q0(1:d), v0(1:d), a0(1:d))
        call kepler_lrl(q(:, 1), v(:, 1), a1(1:d))
        if (d == 2) then
            lz = [0.0_wp, 0.0_wp, 1.0_wp]
        else
            lz = cross(q0, v0)
        end if
        ax = cross(a0, a1)
        precession = atan2(dot_product(ax, lz) / norm2(lz), dot_product(a0, a1))
        call kepler_exact(q0(1:d), v0(1:d), s%time(), qx, vx, st)
        perr = sqrt(sum((q(:, 1) - qx)**2) + sum((v(:, 1) - vx)**2))
    end subroutine diagnose

    pure function cross(a, b) result(c)
        real(wp), intent(in) :: a(3), b(3)
        real(wp) :: c(3)
        c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
    end function cross

    !> Seconds of one whole run (the integration alone, `stepper%run`), wall `t` and thread
    !> CPU `tc`; short runs are repeated `inner` times within the sample (chosen on the first
    !> round) and divided.
    subroutine timed_run(io, im, ie, t, tc)
        integer, intent(in) :: io, im, ie
        real(wp), intent(out) :: t, tc
        type(kepler_model_t) :: model
        class(stepper_t), allocatable :: s
        real(wp) :: q0(3), v0(3), period, h
        real(wp), allocatable :: q(:, :), v(:, :)
        integer(ik) :: nsteps
        integer(int64) :: t1
        integer :: d, r, st
        real(wp) :: c1
        d = DIMS(io)
        call orbit(io, q0, v0, period)
        call run_size(io, nper(ie, im, io), nsteps, h)
        allocate (q(d, 1), v(d, 1))
        c1 = thread_cpu_seconds()
        call system_clock(t1)
        do r = 1, inner(ie, im, io)
            call fsym_new_stepper(trim(names(im)), model, d, 1, s, st, msg)
            q(:, 1) = q0(1:d); v(:, 1) = v0(1:d)
            call s%run(model, q, v, h, nsteps, st)
        end do
        t = seconds_since(t1) / inner(ie, im, io)
        tc = (thread_cpu_seconds() - c1) / inner(ie, im, io)
        if (c1 < 0.0_wp) tc = ieee_nan()
        if (ieee_is_nan(samples(1, ie, im, io)) .and. t * inner(ie, im, io) &
            < TMIN_RUN) then               ! first round: fix the inner repetitions
            inner(ie, im, io) = min(1000, ceiling(TMIN_RUN / max(t, 1.0e-7_wp)))
        end if
    end subroutine timed_run

    !> Measured cost of a gradient evaluation relative to a force evaluation (Kepler model,
    !> one body, through the model's type-bound procedures, thread CPU time): `cost` is the
    !> ratio of the minima over NGPAIR interleaved pairs, `pair` the ratio within each pair.
    subroutine gradient_cost(cost, pair)
        real(wp), intent(out) :: cost, pair(NGPAIR)
        type(kepler_model_t) :: model
        real(wp) :: q(2, 1), a(2, 1), g(2, 1), tf(NGPAIR), tg(NGPAIR), sink, c1
        integer :: r, st
        integer(ik) :: k
        integer(int64) :: t1
        integer(ik), parameter :: nloop = 2000000_ik
        q(:, 1) = [0.7_wp, 0.3_wp]
        sink = 0.0_wp
        do r = 1, NGPAIR
            call system_clock(t1)
            c1 = thread_cpu_seconds()
            do k = 1, nloop
                st = 0
                call model%acceleration(q, a, st)
                q(1, 1) = q(1, 1) + 1.0e-18_wp * a(1, 1)
            end do
            tf(r) = cpu_or_wall(c1, t1)
            call system_clock(t1)
            c1 = thread_cpu_seconds()
            do k = 1, nloop
                st = 0
                call model%gradient(q, a, g, st)
                q(1, 1) = q(1, 1) + 1.0e-18_wp * g(1, 1)
            end do
            tg(r) = cpu_or_wall(c1, t1)
            sink = sink + g(1, 1)
        end do
        if (sink <= 0.123_wp .and. sink >= 0.123_wp) write (output_unit, '(a)') '.'
        cost = minval(tg) / minval(tf)
        pair = tg / tf
    end subroutine gradient_cost

    !> Thread CPU seconds since the reading c1, or wall seconds since the count t1 when the
    !> CPU clock cannot be read.
    real(wp) function cpu_or_wall(c1, t1)
        real(wp), intent(in) :: c1
        integer(int64), intent(in) :: t1
        if (c1 < 0.0_wp) then
            cpu_or_wall = seconds_since(t1)
        else
            cpu_or_wall = thread_cpu_seconds() - c1
        end if
    end function cpu_or_wall

    !> Order of accuracy of every method (RKN: 4).
    subroutine method_orders()
        type(scheme_t) :: sc
        integer :: j, st2
        do j = 1, nm
            ordm(j) = 4
            if (trim(names(j)) == 'RKN') cycle
            call fsym_scheme_by_name(trim(names(j)), sc, st2)
            if (st2 == FSYM_SUCCESS) ordm(j) = sc%order
        end do
    end subroutine method_orders

    !> The CSV of every run (temporary name, renamed).
    subroutine write_csv()
        integer :: u
        call fsym_open_text(trim(csv_path), u, st, msg)
        if (st /= FSYM_SUCCESS) call die(msg)
        write (u, '(a)') 'orbit,d,method,forward,steps_per_period,time_min_s,time_median_s,'// &
            'time_max_s,force_evals,grad_evals,max_rel_energy_error,precession_rad,'// &
            'phase_error,cpu_min_s,cpu_median_s,cpu_max_s'
        do io = 1, NORBIT
            do im = 1, nm
                do ie = 1, npt(im, io)
                    write (u, '(i0,a,i0,a,a,a,l1,12(a,es12.5))') io, ',', DIMS(io), ',', &
                        trim(names(im)), ',', fwd(im), ',', nper(ie, im, io), ',', &
                        tmin(ie, im, io), ',', tmed(ie, im, io), ',', tmax(ie, im, io), ',', &
                        nfe(ie, im, io), ',', nge(ie, im, io), ',', de(ie, im, io), ',', &
                        prec(ie, im, io), ',', phase(ie, im, io), ',', cmin(ie, im, io), ',', &
                        cmed(ie, im, io), ',', cmax(ie, im, io)
                end do
            end do
        end do
        call fsym_commit_text(u, trim(csv_path), st, msg)
        if (st /= FSYM_SUCCESS) call die(msg)
    end subroutine write_csv

    !> Every measured quantity to HDF5 (atomic): per orbit group, per method a group with
    !> one value per step size.
    subroutine write_h5()
        type(h5_file_t) :: f
        character(len=:), allocatable :: g
        integer :: n
        call f%create(trim(h5_path), st, msg)
        if (st /= FSYM_SUCCESS) call die(msg)
        call fsym_h5md_header(f, 'fsym-workprec', FSYM_VERSION, 'Kepler units: G M = 1, '// &
                              'm = 1; run times in seconds (wall clock, and CPU time of '// &
                              'the thread)', st, msg)
        call h5ok(f)
        call f%set_attr('parameters', 'hardware', trim(hardware), st, msg); call h5ok(f)
        call f%set_attr('parameters', 'build_flags', trim(flags), st, msg); call h5ok(f)
        call f%set_attr('parameters', 'mu', 1.0_wp, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'gradient_cost', gcost, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'gradient_cost_pairs', gpair, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'gradient_cost_clock', 'thread CPU time', st, msg)
        call h5ok(f)
        call f%set_attr('parameters', 'repetitions', nreps, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'total_seconds', t_all, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'base_grid', [NMIN, nmax], st, msg); call h5ok(f)
        call f%set_attr('parameters', 'base_points', nsweep, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'energy_targets', ETARGET, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'precession_target', PTARGET, st, msg); call h5ok(f)
        call f%set_attr('parameters', 'methods', names, st, msg); call h5ok(f)
        do io = 1, NORBIT
            call f%set_attr(trim(GROUP(io)), 'description', trim(ORBIT_NAME(io)), st, msg)
            call h5ok(f)
            call f%set_attr(trim(GROUP(io)), 'dimension', DIMS(io), st, msg); call h5ok(f)
            call f%set_attr(trim(GROUP(io)), 'periods', PERIODS(io), st, msg); call h5ok(f)
            do im = 1, nm
                n = npt(im, io)
                g = trim(GROUP(io))//'/'//fsym_h5_safe_name(names(im))
                call f%set_attr(g, 'label', trim(names(im)), st, msg); call h5ok(f)
                call f%set_attr(g, 'forward', merge(1, 0, fwd(im)), st, msg); call h5ok(f)
                call f%set_attr(g, 'order', ordm(im), st, msg); call h5ok(f)
                call f%write(g//'/steps_per_period', nper(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/time_min', tmin(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/time_median', tmed(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/time_max', tmax(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/inner_repeats', inner(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/cpu_min', cmin(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/cpu_median', cmed(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/cpu_max', cmax(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/time_samples', samples(:, 1:n, im, io), st, msg)
                call h5ok(f)
                call f%write(g//'/cpu_samples', csamples(:, 1:n, im, io), st, msg)
                call h5ok(f)
                call f%write(g//'/force_evals', nfe(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/grad_evals', nge(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/max_rel_energy_error', de(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/precession_rad', prec(1:n, im, io), st, msg); call h5ok(f)
                call f%write(g//'/phase_error', phase(1:n, im, io), st, msg); call h5ok(f)
                call f%set_attr(g//'/time_min', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/time_median', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/time_max', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/cpu_min', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/cpu_median', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/cpu_max', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/time_samples', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/cpu_samples', 'unit', 's', st, msg); call h5ok(f)
                call f%set_attr(g//'/precession_rad', 'unit', 'rad', st, msg); call h5ok(f)
            end do
        end do
        call f%close(st, msg)
        if (st /= FSYM_SUCCESS) call die('HDF5 output failed: '//msg)
    end subroutine write_h5

    !> After an HDF5 call: on failure abort the file (no output) and stop with the message.
    subroutine h5ok(f)
        type(h5_file_t), intent(inout) :: f
        if (st /= FSYM_SUCCESS) then
            call f%abort()
            call die('HDF5 output failed: '//msg)
        end if
    end subroutine h5ok

end program fsym_workprec
