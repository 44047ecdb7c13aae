!> The stability study (issue 5): linear stability intervals from the coefficient tables, the
!> stiff linear chain (LAPACK eigenvalues), the stiff FPU problem, extreme eccentricities and
!> near collisions, and a long run of the e = 0.9 orbit. Writes every result to HDF5 (checked
!> writable before the work, written through a temporary name); scripts/report_stability.py
!> renders doc/stability.md from it.
!>
!>     fsym-stability [--periods N] [--nmax N] [--out FILE.h5]
!>
!> --periods: periods of the long run (default 10000; the issue asks for 1e6, about 8 min per
!> method at 0.5 us per step); --nmax: largest steps per period tried for the extreme orbits
!> (default 524288).
program fsym_stability_study
    use, intrinsic :: iso_fortran_env, only: output_unit
    use fsym
    use fsym_linear_stability
    use fsym_fpu
    use fsym_stability_runs
    use fsym_h5, only: h5_file_t, fsym_check_writable, fsym_h5md_header, fsym_exit_failure
    implicit none

    character(len=FSYM_NAME_LEN), allocatable :: names(:)
    integer :: nm
    ! section 1: oscillator
    real(wp), allocatable :: xstar(:), xnext(:), evals(:), growth(:, :), trace_curve(:, :)
    real(wp), allocatable :: xgrid(:)
    ! section 2: chain
    integer, parameter :: nchain = 8
    real(wp), parameter :: chain_ratio = 1.0e4_wp
    real(wp) :: chain_omega(nchain)
    real(wp), allocatable :: chain_pred(:), chain_meas(:), rho_curve(:, :), hgrid(:)
    character(len=FSYM_NAME_LEN), parameter :: curve_names(6) = [character(len=FSYM_NAME_LEN) :: &
        'T2', 'FR', 'A', 'C', 'BM', 'RKN']
    ! section 3: FPU
    integer, parameter :: fpu_m = 3, nfrac = 5, nsamp = 201
    real(wp), parameter :: fpu_omega = 50.0_wp, fpu_t = 200.0_wp, scan_t = 50.0_wp
    real(wp), parameter :: fracs(nfrac) = [0.25_wp, 0.5_wp, 0.75_wp, 0.9_wp, 0.99_wp]
    real(wp), allocatable :: fpu_dh(:, :), fpu_di(:, :), fpu_samples(:, :, :, :)
    integer, allocatable :: fpu_stat(:, :), fpu_ns(:, :)
    real(wp), allocatable :: scan_x(:), scan_dh(:, :)
    logical, allocatable :: scan_flag(:, :)
    ! section 4: eccentric orbits
    integer, parameter :: necc = 4, ngridmax = 48
    real(wp), parameter :: eccs(necc) = [0.9_wp, 0.99_wp, 0.999_wp, 0.9999_wp]
    integer(ik), allocatable :: needed(:, :), broken(:, :), egrid(:, :, :)
    real(wp), allocatable :: eerr(:, :, :)
    integer, allocatable :: eout(:, :, :), engrid(:, :)
    type(kepler_run_t), allocatable :: near(:, :)
    ! section 5: long time
    character(len=FSYM_NAME_LEN), parameter :: long_names(4) = [character(len=FSYM_NAME_LEN) :: &
        'A', 'C', 'FR', 'RKN']
    type(kepler_run_t) :: long_run(4)
    real(wp), allocatable :: long_de(:, :), long_dl(:, :)
    real(wp) :: long_slope(4), long_secs(4)
    integer(ik) :: nperiods = 10000_ik, nmax = 524288_ik
    character(len=512) :: out_file = 'out/stability.h5'
    integer :: stat
    character(len=512) :: msg

    call parse_arguments()
    call fsym_check_writable(trim(out_file), stat, msg)      ! before hours of work, not after
    if (stat /= 0) call die(msg)
    names = fsym_method_names()
    nm = size(names)
    call section_oscillator()
    call section_chain()
    call section_fpu()
    call section_eccentric()
    call section_near_collision()
    call section_long()
    call write_h5()

contains

    subroutine say(text)
        character(len=*), intent(in) :: text
        write (output_unit, '(a)') text
        flush (output_unit)
    end subroutine say

    subroutine die(text)
        character(len=*), intent(in) :: text
        call fsym_exit_failure('fsym-stability', text)
    end subroutine die

    subroutine parse_arguments()
        integer :: k, n, ios
        character(len=512) :: arg, val
        n = command_argument_count()
        k = 1
        do while (k <= n)
            call get_command_argument(k, arg)
            if (k == n .and. arg(1:2) == '--') call die('missing value after '//trim(arg))
            call get_command_argument(k + 1, val)
            select case (trim(arg))
            case ('--periods')
                read (val, *, iostat=ios) nperiods
                if (ios /= 0 .or. nperiods < 1) call die('--periods needs a positive integer')
            case ('--nmax')
                read (val, *, iostat=ios) nmax
                if (ios /= 0 .or. nmax < 16) call die('--nmax needs an integer >= 16')
            case ('--out')
                out_file = val
            case default
                call die('unknown argument '//trim(arg)// &
                         ' (usage: fsym-stability [--periods N] [--nmax N] [--out F])')
            end select
            k = k + 2
        end do
    end subroutine parse_arguments

    !> x* of a method: from its table, or for RKN from the eigenvalues of its step map.
    subroutine method_xstar(name, xs, xn)
        character(len=*), intent(in) :: name
        real(wp), intent(out) :: xs, xn
        type(scheme_t) :: s
        type(oscillator_model_t) :: osc
        if (name == 'RKN') then
            call fsym_stable_step('RKN', osc, 1, 1, 6.0_wp, xs, stat, msg)
            if (stat /= 0) call die(msg)
            xn = huge(1.0_wp)
        else
            call fsym_scheme_by_name(name, s, stat, msg)
            if (stat /= 0) call die(msg)
            call fsym_stability_interval(s, xs, xnext=xn)
        end if
    end subroutine method_xstar

    subroutine section_oscillator()
        type(scheme_t) :: s
        type(oscillator_model_t) :: osc
        real(wp) :: m(2, 2)
        integer :: k, j
        call say('oscillator: stability intervals of every method')
        allocate (xstar(nm), xnext(nm), evals(nm), growth(2, nm))
        xgrid = [(0.01_wp * j, j = 0, 400)]
        allocate (trace_curve(size(xgrid), nm))
        do k = 1, nm
            call method_xstar(trim(names(k)), xstar(k), xnext(k))
            if (names(k) == 'RKN') then
                evals(k) = 3.0_wp
                do j = 1, size(xgrid)
                    call fsym_linear_step_map('RKN', osc, 1, 1, max(xgrid(j), 1.0e-300_wp), m, &
                                              stat, msg)
                    trace_curve(j, k) = m(1, 1) + m(2, 2)
                end do
            else
                call fsym_scheme_by_name(names(k), s, stat, msg)
                evals(k) = real(s%nforce + s%ngrad, wp)
                do j = 1, size(xgrid)
                    trace_curve(j, k) = fsym_oscillator_trace(s, xgrid(j))
                end do
            end if
            call fsym_oscillator_growth(trim(names(k)), 0.99_wp * xstar(k), 20000, growth(1, k))
            call fsym_oscillator_growth(trim(names(k)), xstar(k) + &
                min(0.01_wp * xstar(k), 0.5_wp * (xnext(k) - xstar(k))), 20000, growth(2, k))
        end do
    end subroutine section_oscillator

    subroutine section_chain()
        type(spring_chain_model_t) :: chain
        real(wp) :: map(2 * nchain, 2 * nchain), hmax
        integer :: k, j, i
        call say('chain: stable steps from dgeev')
        call fsym_linear_chain(nchain, chain_ratio, chain, stat, msg)
        if (stat /= 0) call die(msg)
        call fsym_linear_frequencies(chain, 1, nchain, chain_omega, stat, msg)
        if (stat /= 0) call die(msg)
        allocate (chain_pred(nm), chain_meas(nm))
        do k = 1, nm
            chain_pred(k) = xstar(k) / chain_omega(nchain)
            ! the scan must resolve the narrowest instability window (SRKN6b: 0.006 in x)
            call fsym_stable_step(trim(names(k)), chain, 1, nchain, 1.25_wp * chain_pred(k), &
                                  chain_meas(k), stat, msg, nscan=2000)
            if (stat /= 0) call die(msg)
        end do
        hmax = 4.0_wp / chain_omega(nchain)
        hgrid = [(hmax * j / 200.0_wp, j = 1, 200)]
        allocate (rho_curve(size(hgrid), size(curve_names)))
        do i = 1, size(curve_names)
            do j = 1, size(hgrid)
                call fsym_linear_step_map(trim(curve_names(i)), chain, 1, nchain, hgrid(j), map, &
                                          stat, msg)
                if (stat /= 0) call die(msg)
                call fsym_spectral_radius(map, rho_curve(j, i), stat, msg)
                if (stat /= 0) call die(msg)
            end do
        end do
    end subroutine section_chain

    subroutine section_fpu()
        integer :: k, i, j, nx
        integer(ik) :: nsteps
        real(wp) :: h, di, samples(2 + fpu_m, 1), xmaxall
        call say('FPU: every method below and near its stability limit')
        allocate (fpu_dh(nfrac, nm), fpu_di(nfrac, nm), fpu_stat(nfrac, nm), fpu_ns(nfrac, nm))
        allocate (fpu_samples(2 + fpu_m, nsamp, nfrac, nm))
        do k = 1, nm
            do i = 1, nfrac
                h = fracs(i) * xstar(k) / fpu_omega
                nsteps = nint(fpu_t / h, ik)
                call fsym_fpu_run(trim(names(k)), fpu_m, fpu_omega, h, nsteps, &
                                  max(1_ik, (nsteps + nsamp - 2) / (nsamp - 1)), &
                                  fpu_samples(:, :, i, k), fpu_ns(i, k), fpu_dh(i, k), &
                                  fpu_di(i, k), fpu_stat(i, k), msg)
            end do
        end do
        call say('FPU: energy error against h omega (resonance scan)')
        xmaxall = maxval(xstar)
        nx = int(xmaxall / 0.02_wp) - 9
        scan_x = [(0.2_wp + 0.02_wp * j, j = 0, nx - 1)]
        allocate (scan_dh(nx, nm), scan_flag(nx, nm))
        scan_dh = -1.0_wp
        scan_flag = .false.
        do k = 1, nm
            do j = 1, nx
                if (scan_x(j) >= xstar(k)) exit
                h = scan_x(j) / fpu_omega
                call fsym_fpu_run(trim(names(k)), fpu_m, fpu_omega, h, nint(scan_t / h, ik), &
                                  huge(1_ik), samples, i, scan_dh(j, k), di, stat, msg)
                if (stat /= 0) scan_dh(j, k) = huge(1.0_wp)
            end do
            call flag_peaks(scan_dh(:, k), scan_flag(:, k))
        end do
    end subroutine section_fpu

    !> Resonant steps: h omega within 0.05 of a multiple of pi, or an isolated peak of the
    !> energy error, 10 times above the geometric mean of the errors 3 grid points either side.
    subroutine flag_peaks(err, flag)
        real(wp), intent(in) :: err(:)
        logical, intent(out) :: flag(:)
        integer :: j, n, lo, hi
        real(wp) :: ref
        n = size(err)
        flag = .false.
        do j = 1, n
            if (err(j) < 0.0_wp) cycle
            if (abs(scan_x(j) - FSYM_PI * nint(scan_x(j) / FSYM_PI)) < 0.05_wp) flag(j) = .true.
            lo = j - 3; hi = j + 3   ! the points 3 either side
            if (lo >= 1 .and. hi <= n) then
                if (err(lo) > 0.0_wp .and. err(hi) > 0.0_wp) then
                    ref = sqrt(err(lo) * err(hi))
                    if (err(j) > 10.0_wp * ref .and. err(j) >= maxval(err(lo + 1:hi - 1))) then
                        flag(j) = .true.
                    end if
                end if
            end if
        end do
    end subroutine flag_peaks

    subroutine section_eccentric()
        integer :: k, i
        call say('Kepler: steps per period needed at e = 0.9 ... 0.9999')
        allocate (needed(necc, nm), broken(necc, nm), egrid(ngridmax, necc, nm))
        allocate (eerr(ngridmax, necc, nm), eout(ngridmax, necc, nm), engrid(necc, nm))
        do k = 1, nm
            do i = 1, necc
                call fsym_kepler_steps_needed(trim(names(k)), eccs(i), 1.0e-6_wp, 16_ik, nmax, &
                                              needed(i, k), broken(i, k), engrid(i, k), &
                                              egrid(:, i, k), eerr(:, i, k), eout(:, i, k))
            end do
        end do
    end subroutine section_eccentric

    !> Near collisions: pericentre 1e-9 at 1000 steps per period, the exact origin as the
    !> start point, and the radial infall (v = 0) through the origin.
    subroutine section_near_collision()
        real(wp) :: q0(2), v0(2), e
        integer :: k
        call say('Kepler: near collisions')
        allocate (near(3, nm))
        do k = 1, nm
            e = 1.0_wp - 1.0e-9_wp
            call kepler_elliptic_orbit(e, q0, v0)
            call fsym_kepler_run(trim(names(k)), q0, v0, 1000_ik, 1_ik, near(1, k))
            q0 = [0.0_wp, 0.0_wp]; v0 = [0.0_wp, 1.0_wp]
            call fsym_kepler_run(trim(names(k)), q0, v0, 1000_ik, 1_ik, near(2, k))
            q0 = [1.0_wp, 0.0_wp]; v0 = [0.0_wp, 0.0_wp]
            call fsym_kepler_run(trim(names(k)), q0, v0, 1000_ik, 1_ik, near(3, k))
            if (any(near(:, k)%outcome == RUN_OK .and. .not. near(:, k)%finite)) then
                call die('silent NaN: '//trim(names(k)))
            end if
        end do
    end subroutine section_near_collision

    subroutine section_long()
        real(wp) :: q0(2), v0(2), t0, t1
        integer :: k
        character(len=64) :: buf
        write (buf, '(a,i0,a)') 'long run: ', nperiods, ' periods of e = 0.9 at P/1000'
        call say(trim(buf))
        allocate (long_de(nperiods, 4), long_dl(nperiods, 4))
        call kepler_elliptic_orbit(0.9_wp, q0, v0)
        do k = 1, 4
            call cpu_time(t0)
            call fsym_kepler_run(trim(long_names(k)), q0, v0, 1000_ik, nperiods, long_run(k), &
                                 long_de(:, k), long_dl(:, k))
            call cpu_time(t1)
            long_secs(k) = t1 - t0
            long_slope(k) = fit_slope(long_de(:, k), long_run(k)%steps / 1000_ik)
        end do
    end subroutine section_long

    !> Least-squares slope of y(1:n) against the period index 1..n.
    pure real(wp) function fit_slope(y, n)
        real(wp), intent(in) :: y(:)
        integer(ik), intent(in) :: n
        real(wp) :: xm, ym, sxy, sxx
        integer(ik) :: i
        fit_slope = 0.0_wp
        if (n < 2) return
        xm = 0.5_wp * real(n + 1, wp)
        ym = sum(y(1:n)) / real(n, wp)
        sxy = 0.0_wp; sxx = 0.0_wp
        do i = 1, n
            sxy = sxy + (real(i, wp) - xm) * (y(i) - ym)
            sxx = sxx + (real(i, wp) - xm)**2
        end do
        fit_slope = sxy / sxx
    end function fit_slope

    !> Names joined by commas (for a string attribute).
    function joined(list) result(t)
        character(len=*), intent(in) :: list(:)
        character(len=:), allocatable :: t
        integer :: k
        t = trim(list(1))
        do k = 2, size(list)
            t = t//','//trim(list(k))
        end do
    end function joined

    !> Every result to HDF5 (through the shared layer: atomic, every status checked).
    !> Fortran (n1, n2) arrays appear in h5py as (n2, n1): per method rows.
    subroutine write_h5()
        type(h5_file_t) :: h5
        integer :: st
        call say('writing '//trim(out_file))
        call h5%create(trim(out_file), st, msg)
        if (st /= 0) call die(msg)
        call fsym_h5md_header(h5, 'fsym-stability', FSYM_VERSION, 'dimensionless (each '// &
                              'model in its own units; Kepler: G M = 1)', st, msg)
        call ok(h5, st)
        call h5%set_attr('/', 'generator', 'fsym-stability', st, msg); call ok(h5, st)
        call h5%set_attr('/', 'methods', joined(names), st, msg); call ok(h5, st)
        call h5%set_attr('/', 'periods', int(nperiods), st, msg); call ok(h5, st)
        ! 1. oscillator
        call h5%write('oscillator/x', xgrid, st, msg); call ok(h5, st)
        call h5%write('oscillator/trace', trace_curve, st, msg); call ok(h5, st)
        call h5%write('oscillator/xstar', xstar, st, msg); call ok(h5, st)
        call h5%write('oscillator/window_end', min(xnext, 40.0_wp), st, msg); call ok(h5, st)
        call h5%write('oscillator/evaluations', evals, st, msg); call ok(h5, st)
        call h5%write('oscillator/growth', growth, st, msg); call ok(h5, st)
        ! 2. chain
        call h5%write('chain/omega', chain_omega, st, msg); call ok(h5, st)
        call h5%write('chain/predicted', chain_pred, st, msg); call ok(h5, st)
        call h5%write('chain/measured', chain_meas, st, msg); call ok(h5, st)
        call h5%write('chain/h', hgrid, st, msg); call ok(h5, st)
        call h5%write('chain/rho', rho_curve, st, msg); call ok(h5, st)
        call h5%set_attr('chain', 'methods', joined(curve_names), st, msg); call ok(h5, st)
        call h5%set_attr('chain', 'ratio', chain_ratio, st, msg); call ok(h5, st)
        ! 3. FPU
        call h5%write('fpu/fractions', fracs, st, msg); call ok(h5, st)
        call h5%write('fpu/max_dH', fpu_dh, st, msg); call ok(h5, st)
        call h5%write('fpu/max_dI', fpu_di, st, msg); call ok(h5, st)
        call h5%write('fpu/status', real(fpu_stat, wp), st, msg); call ok(h5, st)
        call h5%write('fpu/samples_half', fpu_samples(:, :, 2, :), st, msg); call ok(h5, st)
        call h5%write('fpu/nsamples_half', fpu_ns(2, :), st, msg); call ok(h5, st)
        call h5%write('fpu/scan_x', scan_x, st, msg); call ok(h5, st)
        call h5%write('fpu/scan_dh', scan_dh, st, msg); call ok(h5, st)
        call h5%write('fpu/scan_flag', merge(1.0_wp, 0.0_wp, scan_flag), st, msg); call ok(h5, st)
        call h5%set_attr('fpu', 'omega', fpu_omega, st, msg); call ok(h5, st)
        call h5%set_attr('fpu', 'T', fpu_t, st, msg); call ok(h5, st)
        call h5%set_attr('fpu', 'scan_T', scan_t, st, msg); call ok(h5, st)
        call h5%set_attr('fpu', 'm', fpu_m, st, msg); call ok(h5, st)
        call h5%write('fpu/final_I', final_i(), st, msg); call ok(h5, st)
        ! 4. eccentric orbits
        call h5%write('kepler/e', eccs, st, msg); call ok(h5, st)
        call h5%write('kepler/needed', real(needed, wp), st, msg); call ok(h5, st)
        call h5%write('kepler/broken', real(broken, wp), st, msg); call ok(h5, st)
        call h5%write('kepler/grid', real(egrid, wp), st, msg); call ok(h5, st)
        call h5%write('kepler/max_dE', eerr, st, msg); call ok(h5, st)
        call h5%write('kepler/outcome', real(eout, wp), st, msg); call ok(h5, st)
        call h5%set_attr('kepler', 'nmax', int(nmax), st, msg); call ok(h5, st)
        ! 5. near collisions
        call h5%write('near/outcome', real(near%outcome, wp), st, msg); call ok(h5, st)
        call h5%write('near/stat', real(near%stat, wp), st, msg); call ok(h5, st)
        call h5%write('near/max_dE', near%max_de, st, msg); call ok(h5, st)
        call h5%write('near/finite', merge(1, 0, reshape(near%finite, [size(near)])), st, msg)
        call ok(h5, st)
        call h5%set_attr('near', 'outcome_text', run_names(reshape(near, [size(near)])), &
                         st, msg)
        call ok(h5, st)
        call h5%set_attr('near', 'messages', run_messages(reshape(near, [size(near)])), st, msg)
        call ok(h5, st)
        ! 6. long run
        call h5%write('long/de', long_de, st, msg); call ok(h5, st)
        call h5%write('long/dl', long_dl, st, msg); call ok(h5, st)
        call h5%write('long/periods_done', long_run%steps / 1000_ik, st, msg); call ok(h5, st)
        call h5%write('long/max_dE', long_run%max_de, st, msg); call ok(h5, st)
        call h5%write('long/max_dL', long_run%max_dl, st, msg); call ok(h5, st)
        call h5%write('long/slope', long_slope, st, msg); call ok(h5, st)
        call h5%write('long/time', long_run%time, st, msg); call ok(h5, st)
        call h5%set_attr('long/time', 'unit', 'T (Kepler units, G M = 1)', st, msg)
        call ok(h5, st)
        call h5%write('long/cpu_seconds', long_secs, st, msg); call ok(h5, st)
        call h5%set_attr('long', 'outcome_text', run_names(long_run), st, msg); call ok(h5, st)
        call h5%set_attr('long', 'methods', joined(long_names), st, msg); call ok(h5, st)
        call h5%close(st, msg)
        if (st /= 0) call die(msg)
    end subroutine write_h5

    !> I_1 .. I_m and I at the end of the FPU runs at the first two step fractions
    !> (m + 1, 2, methods); -1 where the run was refused or has no sample.
    function final_i() result(a)
        real(wp) :: a(fpu_m + 1, 2, nm)
        integer :: k, i, j
        a = -1.0_wp
        do k = 1, nm
            do i = 1, 2
                if (fpu_stat(i, k) /= 0 .or. fpu_ns(i, k) < 1) cycle
                j = fpu_ns(i, k)
                a(1:fpu_m, i, k) = fpu_samples(3:2 + fpu_m, j, i, k)
                a(fpu_m + 1, i, k) = sum(fpu_samples(3:2 + fpu_m, j, i, k))
            end do
        end do
    end function final_i

    !> Outcome texts of Kepler runs (`fsym_run_name`).
    function run_names(r) result(t)
        type(kepler_run_t), intent(in) :: r(:)
        character(len=24) :: t(size(r))
        integer :: k
        do k = 1, size(r)
            t(k) = fsym_run_name(r(k)%outcome)
        end do
    end function run_names

    !> The stepper's status and message of refused Kepler runs (empty otherwise).
    function run_messages(r) result(t)
        type(kepler_run_t), intent(in) :: r(:)
        character(len=len(r(1)%msg) + 16) :: t(size(r))
        integer :: k
        do k = 1, size(r)
            t(k) = ''
            if (r(k)%outcome == RUN_REFUSED) t(k) = 'stat '//fsym_int_text(r(k)%stat)//': '// &
                                                    trim(r(k)%msg)
        end do
    end function run_messages

    !> After an HDF5 call: on failure delete the temporary file and stop with the message.
    subroutine ok(h5, code)
        type(h5_file_t), intent(inout) :: h5
        integer, intent(in) :: code
        if (code /= 0) then
            call h5%abort()
            call die(msg)
        end if
    end subroutine ok

end program fsym_stability_study
