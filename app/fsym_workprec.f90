!> Work-precision study: every method of the library (the catalogue and RKN) on two Kepler
!> orbits, step sizes P/100 .. P/20000, error against run time and against evaluations, the
!> time each method needs to reach target errors, ranked. Writes the table of every run
!> (CSV, read by scripts/plot_workprec.py) and the report `doc/work-precision.md`.
!>
!> Usage:
!>   fsym-workprec [md csv h5 hardware compiler flags [nsweep2 [nsweep1 [Nmax]]]]
!> The hardware, compiler and flags strings are printed into the report as given. The HDF5
!> file holds, per orbit group (`e0.9`, `e0.6`), 2D datasets (step size x method) of every
!> measured quantity, the method names and the run's description as attributes.
program fsym_workprec
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_timing, only: seconds_since, median
    use fsym_h5, only: h5_file_t
    implicit none

    integer, parameter :: norbit = 2
    real(wp), parameter :: nmin = 100.0_wp   ! steps per period, coarsest
    real(wp) :: nmax = 20000.0_wp            ! steps per period, finest
    character(len=FSYM_NAME_LEN), allocatable :: names(:)
    character(len=512) :: md_path, csv_path, h5_path, hardware, compiler, flags, arg
    integer :: nsweep(norbit), nm, io, ie, im, u
    real(wp), allocatable :: tim(:, :, :), de(:, :, :), prec(:, :, :), phase(:, :, :)
    real(wp), allocatable :: nfe(:, :, :), nge(:, :, :), steps_per_period(:, :)
    logical, allocatable :: fwd(:)
    integer, allocatable :: ordm(:)
    real(wp) :: gcost, t_start
    integer(int64) :: t0

    md_path = 'doc/work-precision.md'
    csv_path = 'doc/work-precision.csv'
    h5_path = 'out/work-precision.h5'
    hardware = 'unknown'; compiler = 'unknown'; flags = 'unknown'
    nsweep = [12, 12]
    if (command_argument_count() >= 6) then
        call get_command_argument(1, md_path)
        call get_command_argument(2, csv_path)
        call get_command_argument(3, h5_path)
        call get_command_argument(4, hardware)
        call get_command_argument(5, compiler)
        call get_command_argument(6, flags)
    end if
    if (command_argument_count() >= 7) then
        call get_command_argument(7, arg)
        read (arg, *) nsweep(2)
    end if
    if (command_argument_count() >= 8) then
        call get_command_argument(8, arg)
        read (arg, *) nsweep(1)
    end if
    if (command_argument_count() >= 9) then      ! finest N (a quick smoke test)
        call get_command_argument(9, arg)
        read (arg, *) nmax
    end if
    nsweep = max(2, nsweep)
    call system_clock(t0)

    names = fsym_method_names()
    nm = size(names)
    allocate (tim(maxval(nsweep), nm, norbit))
    allocate (de, prec, phase, nfe, nge, mold=tim)
    allocate (steps_per_period(maxval(nsweep), norbit), fwd(nm), ordm(nm))
    call method_orders()
    tim = -1.0_wp; de = ieee_nan(); prec = ieee_nan(); phase = ieee_nan()
    nfe = 0.0_wp; nge = 0.0_wp
    gcost = gradient_cost()
    write (output_unit, '(a,f0.3)') 'gradient cost / force cost = ', gcost

    do io = 1, norbit
        do ie = 1, nsweep(io)
            steps_per_period(ie, io) = nmin * (nmax / nmin)**(real(ie - 1, wp) / &
                                                               real(nsweep(io) - 1, wp))
        end do
        do im = 1, nm
            do ie = 1, nsweep(io)
                call one_run(io, trim(names(im)), steps_per_period(ie, io), fwd(im), &
                             tim(ie, im, io), nfe(ie, im, io), nge(ie, im, io), de(ie, im, io), &
                             prec(ie, im, io), phase(ie, im, io))
            end do
            write (output_unit, '(a,i0,a,a,a,f0.1,a)') 'orbit ', io, ' ', trim(names(im)), &
                ' done (', seconds_since(t0), ' s)'
            flush (output_unit)
        end do
    end do
    t_start = seconds_since(t0)

    open (newunit=u, file=trim(csv_path), status='replace', action='write')
    write (u, '(a)') 'orbit,method,forward,steps_per_period,time_s,force_evals,grad_evals,'// &
        'max_rel_energy_error,precession_rad,phase_error'
    do io = 1, norbit
        do im = 1, nm
            do ie = 1, nsweep(io)
                write (u, '(i0,a,a,a,l1,a,es12.5,a,es12.5,a,es12.5,a,es12.5,a,es12.5,a,'// &
                       'es12.5,a,es12.5)') io, ',', trim(names(im)), ',', fwd(im), ',', &
                    steps_per_period(ie, io), ',', tim(ie, im, io), ',', nfe(ie, im, io), ',', &
                    nge(ie, im, io), ',', de(ie, im, io), ',', prec(ie, im, io), ',', &
                    phase(ie, im, io)
            end do
        end do
    end do
    close (u)
    call write_report()
    call write_h5()
    write (output_unit, '(a)') 'wrote '//trim(md_path)//', '//trim(csv_path)//' and '// &
        trim(h5_path)

contains

    real(wp) function ieee_nan()
        use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
        ieee_nan = ieee_value(1.0_wp, ieee_quiet_nan)
    end function ieee_nan

    !> Initial state, period and number of periods of orbit `io`.
    subroutine orbit(io, q, v, period, nper)
        integer, intent(in) :: io
        real(wp), intent(out) :: q(2), v(2), period
        integer, intent(out) :: nper
        if (io == 1) then
            call kepler_paper_orbit(q, v, period)
            nper = 10
        else
            call kepler_elliptic_orbit(0.6_wp, q, v, period)
            nper = 200
        end if
    end subroutine orbit

    !> One method at one step size on orbit io: a diagnostic run (energy after every step,
    !> LRL angle and the exact solution at the end), then timed runs with nothing but the
    !> integration in the loop (median of 3 to 7 repeats).
    subroutine one_run(io, name, nper_period, forward, time, nf, ng, dmax, precession, perr)
        integer, intent(in) :: io
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: nper_period
        logical, intent(out) :: forward
        real(wp), intent(out) :: time, nf, ng, dmax, precession, perr
        type(kepler_model_t) :: model
        class(stepper_t), allocatable :: s
        real(wp) :: q0(2), v0(2), period, h, q(2, 1), v(2, 1), e0, qx(2), vx(2), ang0, reps(7)
        integer :: nper, st, r, nrep
        integer(ik) :: k, nsteps
        integer(int64) :: t1
        character(len=256) :: msg

        call orbit(io, q0, v0, period, nper)
        nsteps = nint(nper_period * nper, ik)
        h = period * nper / real(nsteps, wp)
        call fsym_new_stepper(name, model, 2, 1, s, st, msg)
        if (st /= FSYM_SUCCESS) then
            write (output_unit, '(a)') 'fsym-workprec: '//trim(msg)
            error stop 1
        end if
        forward = s%is_forward()
        q(:, 1) = q0; v(:, 1) = v0
        e0 = kepler_energy(q0, v0)
        ang0 = kepler_lrl_angle(q0, v0)
        dmax = 0.0_wp
        do k = 1, nsteps
            call s%step(model, q, v, h, st)
            if (st /= FSYM_SUCCESS) exit
            dmax = max(dmax, abs((kepler_energy(q(:, 1), v(:, 1)) - e0) / e0))
        end do
        nf = real(s%force_evaluations(), wp)
        ng = real(s%gradient_evaluations(), wp)
        time = ieee_nan()
        if (st /= FSYM_SUCCESS) then
            dmax = ieee_nan(); precession = ieee_nan(); perr = ieee_nan()
            return
        end if
        precession = kepler_lrl_angle(q(:, 1), v(:, 1)) - ang0
        precession = atan2(sin(precession), cos(precession))
        call kepler_exact(q0, v0, s%time(), qx, vx, st)
        perr = sqrt(sum((q(:, 1) - qx)**2) + sum((v(:, 1) - vx)**2))

        nrep = 3
        do r = 1, size(reps)
            call fsym_new_stepper(name, model, 2, 1, s, st, msg)
            q(:, 1) = q0; v(:, 1) = v0
            call system_clock(t1)
            call s%run(model, q, v, h, nsteps, st)
            reps(r) = seconds_since(t1)
            if (r == 1 .and. reps(1) < 0.02_wp) nrep = size(reps)
            if (r >= nrep) exit
        end do
        time = median(reps(1:nrep))
    end subroutine one_run

    !> Measured cost of a gradient evaluation relative to a force evaluation (Kepler model,
    !> one body, through the model's type-bound procedures; median of 7).
    real(wp) function gradient_cost()
        type(kepler_model_t) :: model
        real(wp) :: q(2, 1), a(2, 1), g(2, 1), tf(7), tg(7), sink
        integer :: r, st
        integer(ik) :: k
        integer(int64) :: t1
        integer(ik), parameter :: nloop = 2000000_ik
        q(:, 1) = [0.7_wp, 0.3_wp]
        sink = 0.0_wp
        do r = 1, 7
            call system_clock(t1)
            do k = 1, nloop
                st = 0
                call model%acceleration(q, a, st)
                q(1, 1) = q(1, 1) + 1.0e-18_wp * a(1, 1)
            end do
            tf(r) = seconds_since(t1)
            call system_clock(t1)
            do k = 1, nloop
                st = 0
                call model%gradient(q, a, g, st)
                q(1, 1) = q(1, 1) + 1.0e-18_wp * g(1, 1)
            end do
            tg(r) = seconds_since(t1)
            sink = sink + g(1, 1)
        end do
        if (sink == 0.123_wp) write (output_unit, '(a)') '.'
        gradient_cost = median(tg) / median(tf)
    end function gradient_cost

    !> Time at which the error first falls to `target` along the sweep (coarse to fine),
    !> interpolated in log-log between the two bracketing runs. -1 when never reached; the
    !> time of the coarsest run (flagged by `coarse`) when already reached there.
    real(wp) function time_to(err, t, n, target, coarse)
        real(wp), intent(in) :: err(:), t(:), target
        integer, intent(in) :: n
        logical, intent(out) :: coarse
        integer :: k
        real(wp) :: f
        time_to = -1.0_wp
        coarse = .false.
        do k = 1, n
            if (.not. (err(k) <= target)) cycle
            if (.not. (t(k) > 0.0_wp)) cycle
            if (k == 1) then
                time_to = t(1); coarse = .true.
            else if (.not. (err(k - 1) > target .and. t(k - 1) > 0.0_wp .and. &
                            err(k - 1) < huge(1.0_wp))) then
                time_to = t(k)
            else
                f = log(target / err(k - 1)) / log(err(k) / err(k - 1))
                time_to = exp(log(t(k - 1)) + f * (log(t(k)) - log(t(k - 1))))
            end if
            return
        end do
    end function time_to

    !> The markdown report.
    subroutine write_report()
        integer, parameter :: ntarget = 5
        character(len=64) :: tname(ntarget)
        integer :: tio(ntarget), kt, j, rank, order(nm), iu, nreach
        real(wp) :: ttarget(nm), tval(ntarget), etarget(size(de, 1)), nfirst
        logical :: coarse(nm)
        character(len=16) :: cell, kind

        tname = [character(len=64) :: 'max abs(dE/E) <= 1e-4, e = 0.9 orbit, 10 periods', &
                 'max abs(dE/E) <= 1e-8, e = 0.9 orbit, 10 periods', &
                 'abs(precession) <= 1e-6 rad after 10 periods (e = 0.9)', &
                 'max abs(dE/E) <= 1e-4, e = 0.6 orbit, 200 periods', &
                 'max abs(dE/E) <= 1e-8, e = 0.6 orbit, 200 periods']
        tio = [1, 1, 1, 2, 2]
        tval = [1.0e-4_wp, 1.0e-8_wp, 1.0e-6_wp, 1.0e-4_wp, 1.0e-8_wp]

        open (newunit=iu, file=trim(md_path), status='replace', action='write')
        write (iu, '(a)') '# Work-precision: error against run time', '', &
            'Generated by `bash scripts/workprec.sh` (program `fsym-workprec`, plot by '// &
            '`scripts/plot_workprec.py`); every number below comes from that run. The raw '// &
            'table of every run is `doc/work-precision.csv`.', '', &
            '- Hardware: '//trim(hardware), '- Compiler: '//trim(compiler), &
            '- Flags: `'//trim(flags)//'`'
        write (iu, '(a,f0.1,a)') '- Total run time of the study: ', t_start, ' s'
        write (iu, '(a)') '- The machine was shared with other jobs while this ran: times '// &
            'are medians of 3 to 7 repeats but still noisy (a few 10 %).', '', &
            '## Setup', '', &
            '- Orbits: the paper''s q = (10, 0), v = (0, 0.1) (e = 0.9) over 10 periods, and '// &
            'the Hairer-Lubich-Wanner orbit q = (0.4, 0), v = (0, 2) (e = 0.6) over 200 periods.'
        write (iu, '(a,i0,a,i0,a)') '- Step sizes: eps = P/N with N geometric from 100 to '// &
            '20000, ', nsweep(1), ' values on the e = 0.9 orbit, ', nsweep(2), &
            ' on the e = 0.6 orbit.'
        write (iu, '(a)') '- Per run: wall time of the integration alone (`stepper%run`, '// &
            'system_clock, median of 3 repeats, of 7 when a run is shorter than 20 ms), '// &
            'force and gradient evaluations (the library''s counters), max relative energy '// &
            'error over every step, precession of the LRL vector at the end, phase-space error '// &
            'at the end against `kepler_exact` (diagnostics in a separate, untimed run).', &
            '- All methods use the library''s Kepler model. The splitting methods take the '// &
            'kernel''s specialised Kepler path: `integrator_t%run` runs every step in one '// &
            'kernel call, at the cost of a hand-written loop (`doc/benchmarks.md`). RKN is '// &
            'its own stepper and calls the model''s type-bound `acceleration` for each of '// &
            'its evaluations, so part of its time is call overhead the splitting methods do '// &
            'not pay; the plot against evaluations is free of it.'
        write (iu, '(a,f0.3,a)') '- Measured cost of a gradient evaluation relative to a '// &
            'force evaluation (Kepler model, one body): ', gcost, '; the plot''s '// &
            '"effective evaluations" are F + that ratio x G.'
        write (iu, '(a)') '', '![work-precision](figures/work-precision.png)', ''

        write (iu, '(a)') '## Time to reach a target error, ranked', '', &
            'Time of a whole run (the stated number of periods) interpolated log-log between '// &
            'the two sweep points that bracket the target. `<=` : already reached at the '// &
            'coarsest step P/100 (the time shown is that run''s). `-` : not reached at P/20000 '// &
            '(or the run failed). F = forward method (all weights >= 0).', ''
        do kt = 1, ntarget
            do j = 1, nm
                select case (kt)
                case (3)
                    etarget = abs(prec(:, j, tio(kt)))
                case default
                    etarget = de(:, j, tio(kt))
                end select
                ttarget(j) = time_to(etarget(1:nsweep(tio(kt))), tim(:, j, tio(kt)), &
                                     nsweep(tio(kt)), tval(kt), coarse(j))
            end do
            call rank_order(ttarget, order)
            write (iu, '(a)') '### '//trim(tname(kt)), '', &
                '| rank | method | kind | order | time to target (ms) |', '|---|---|---|---|---|'
            rank = 0
            nreach = 0
            do j = 1, nm
                im = order(j)
                kind = merge('F          ', 'non-forward', fwd(im))
                if (trim(names(im)) == 'RKN') kind = 'RKN'
                if (ttarget(im) > 0.0_wp) then
                    rank = rank + 1
                    nreach = nreach + 1
                    cell = ms(ttarget(im))
                    if (coarse(im)) cell = '<= '//trim(cell)
                    write (iu, '(a,i0,a,i0,a)') '| ', rank, ' | '//trim(names(im))//' | '// &
                        trim(kind)//' | ', ordm(im), ' | '//trim(cell)//' |'
                else
                    write (iu, '(a,i0,a)') '| - | '//trim(names(im))//' | '//trim(kind)//' | ', &
                        ordm(im), ' | - |'
                end if
            end do
            nfirst = count(fwd(order(1:min(5, nreach))))
            write (iu, '(a)') ''
            call compare(iu, 'All splitting methods', ttarget, 0)
            call compare(iu, 'Fourth-order splitting methods only (the paper''s comparison)', &
                         ttarget, 4)
            write (iu, '(a,i0,a)') '- Forward methods among the five fastest: ', nint(nfirst), '.'
            write (iu, '(a)') ''
        end do
        close (iu)
    end subroutine write_report

    !> Every measured quantity to the HDF5 file (written atomically by `fsym_h5`).
    subroutine write_h5()
        type(h5_file_t) :: f
        character(len=8), parameter :: grp(norbit) = [character(len=8) :: 'e0.9', 'e0.6']
        integer, parameter :: nper(norbit) = [10, 200]
        character(len=:), allocatable :: list, g
        character(len=512) :: msg
        integer :: st, j, k
        list = trim(names(1))
        do j = 2, nm
            list = list//','//trim(names(j))
        end do
        msg = ''
        call f%create(trim(h5_path), st, msg)
        if (st /= FSYM_SUCCESS) then
            write (output_unit, '(a)') 'fsym-workprec: '//trim(msg)
            error stop 1
        end if
        call f%set_attr('/', 'methods', list, st, msg)
        if (st == FSYM_SUCCESS) call f%set_attr('/', 'hardware', trim(hardware), st, msg)
        if (st == FSYM_SUCCESS) call f%set_attr('/', 'compiler', trim(compiler), st, msg)
        if (st == FSYM_SUCCESS) call f%set_attr('/', 'flags', trim(flags), st, msg)
        if (st == FSYM_SUCCESS) call f%set_attr('/', 'gradient_cost', gcost, st, msg)
        if (st == FSYM_SUCCESS) call f%write('forward', merge(1, 0, fwd), st, msg)
        do j = 1, norbit
            if (st /= FSYM_SUCCESS) exit
            g = trim(grp(j)); k = nsweep(j)
            call f%make_group(g, st, msg)
            if (st == FSYM_SUCCESS) call f%set_attr(g, 'periods', nper(j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/steps_per_period', &
                                                 steps_per_period(1:k, j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/time_s', tim(1:k, :, j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/force_evals', nfe(1:k, :, j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/grad_evals', nge(1:k, :, j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/max_rel_energy_error', &
                                                 de(1:k, :, j), st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/precession_rad', prec(1:k, :, j), &
                                                 st, msg)
            if (st == FSYM_SUCCESS) call f%write(g//'/phase_error', phase(1:k, :, j), &
                                                 st, msg)
        end do
        if (st == FSYM_SUCCESS) then
            call f%close(st, msg)
        else
            call f%abort()
        end if
        if (st /= FSYM_SUCCESS) then
            write (output_unit, '(a)') 'fsym-workprec: HDF5 output failed: '//trim(msg)
            error stop 1
        end if
    end subroutine write_h5

    !> One line: fastest forward against fastest non-forward splitting method (RKN excluded),
    !> among methods of order `only` (0: all).
    subroutine compare(iu, label, t, only)
        integer, intent(in) :: iu, only
        character(len=*), intent(in) :: label
        real(wp), intent(in) :: t(:)
        integer :: j, bf, bn
        bf = 0; bn = 0
        do j = 1, nm
            if (.not. (t(j) > 0.0_wp) .or. trim(names(j)) == 'RKN') cycle
            if (only > 0 .and. ordm(j) /= only) cycle
            if (fwd(j)) then
                if (bf == 0) then
                    bf = j
                else if (t(j) < t(bf)) then
                    bf = j
                end if
            else
                if (bn == 0) then
                    bn = j
                else if (t(j) < t(bn)) then
                    bn = j
                end if
            end if
        end do
        if (bf == 0 .or. bn == 0) then
            write (iu, '(a)') '- '//label//': one of the two kinds never reached the target.'
            return
        end if
        write (iu, '(a)') '- '//label//': fastest forward '//trim(names(bf))//' ('// &
            trim(ms(t(bf)))//' ms), fastest non-forward '//trim(names(bn))//' ('// &
            trim(ms(t(bn)))//' ms): '//trim(verdict(t(bn) / t(bf)))//' (ratio non-forward/'// &
            'forward '//trim(ratio(t(bn) / t(bf)))//').'
    end subroutine compare

    !> Who wins at a ratio (time non-forward / time forward); within 15 % (the timing noise
    !> of a shared machine) a tie.
    function verdict(r) result(text)
        real(wp), intent(in) :: r
        character(len=48) :: text
        if (r > 1.15_wp) then
            text = 'forward wins'
        else if (r < 1.0_wp / 1.15_wp) then
            text = 'non-forward wins'
        else
            text = 'a tie within the timing noise (15 %)'
        end if
    end function verdict

    !> Seconds as milliseconds, 3 decimals.
    function ms(t) result(text)
        real(wp), intent(in) :: t
        character(len=16) :: text
        write (text, '(f16.3)') 1.0e3_wp * t
        text = adjustl(text)
    end function ms

    !> A ratio with 2 decimals.
    function ratio(x) result(text)
        real(wp), intent(in) :: x
        character(len=16) :: text
        write (text, '(f16.2)') x
        text = adjustl(text)
    end function ratio

    !> Order of accuracy of every method (RKN: 4).
    subroutine method_orders()
        type(scheme_t) :: sc
        integer :: j, st
        do j = 1, nm
            ordm(j) = 4
            if (trim(names(j)) == 'RKN') cycle
            call fsym_scheme_by_name(trim(names(j)), sc, st)
            if (st == FSYM_SUCCESS) ordm(j) = sc%order
        end do
    end subroutine method_orders

    !> Indices sorting t ascending, with the non-positive (not reached) last.
    subroutine rank_order(t, order)
        real(wp), intent(in) :: t(:)
        integer, intent(out) :: order(:)
        integer :: i, j, k
        real(wp) :: key(size(t))
        key = t
        where (.not. (key > 0.0_wp)) key = huge(1.0_wp)
        order = [(i, i=1, size(t))]
        do i = 2, size(t)
            k = order(i); j = i - 1
            do while (j >= 1)
                if (key(order(j)) <= key(k)) exit
                order(j + 1) = order(j); j = j - 1
            end do
            order(j + 1) = k
        end do
    end subroutine rank_order

end program fsym_workprec
