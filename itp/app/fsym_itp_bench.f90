!> Benchmark of the imaginary-time propagator (issue 26): energy error against tau, FFTs and
!> wall time per method, on problems with exact or converged answers:
!>   ho3d  3-D isotropic harmonic oscillator, 32^3 points, box 12, E0 = 3/2 exactly;
!>   pt1d  1-D Poeschl-Teller well, lambda = 3, 256 points, box 40, E0 = -9/2 exactly;
!>   gp3d  3-D anisotropic Gross-Pitaevskii ground state, trap (1, 1.5, 2), g = 20, 36^3
!>         points, box 10, against A5 at tau = 0.005 on the same grid (converged in tau; its
!>         resolution is checked and printed).
!> Methods: CN (split-step Crank-Nicolson), the two Strang forms V/2 T V/2 (`Strang`) and
!> T/2 V T/2 (`TVT`, drifts merged across steps), Chin's forward A, B, C and A4-A6, and the
!> multi-product expansions MP4, MP6, MP8 (of Strang) and A-MP6 (of A).
!> Every run starts from the same Gaussian and runs t = 16, long
!> enough that the excited components are below 1e-12; the relative error of <H> is then the
!> method's. Per method a sweep of tau (dividing by sqrt 2 from tau0 = 3.2, 0.4 for Strang,
!> 0.05 for CN; a first step that fails is skipped) until the error is below 1e-12
!> (`--quick`: 1e-10). FFTs and seconds to 1e-8 (and, on # lines, to 1e-10 and 1e-12) are
!> interpolated log-log between the two sweep points around the tolerance (`--quick` stops a
!> sweep whose next point would exceed 20000 FFTs in 3-D, the full run 400000; a value
!> beyond the sweep is extrapolated with the fitted order and flagged). The FFTs are exact
!> counts (`fft_per_step` times the interpolated number of steps). Seconds per step come from
!> a separate timing pass: blocks of steps of every method interleaved, 7 repetitions, the
!> minimum taken, the spread printed. Per problem and tolerance a `# summary` line compares
!> the best forward method with the cheaper Strang form and with CN, and `# check` lines run
!> the winner and the Strang baseline at 1e-8 with the next whole number of steps (the
!> interpolation's check). Output, per problem and method:
!>   itp problem=NAME method=M order=P ffts_to_1e-8=N seconds_to_1e-8=S
!> and `#` lines with the sweep (tau, error, FFTs), the timing spread, the tolerances.
!> The same runs also give the norm-decay energy `e_norm` (its relative error against E0, for
!> gp3d against the reference chemical potential mu = <T + V + g psi^2> of the reference
!> state, the limit of e_norm); its sweep goes on after the <H> sweep's end, down to 1e-12
!> (`--quick`: 1e-9; capped at 50000 FFTs of a 3-D run, `--quick` 10000). Its error is of
!> the method's order, not twice it, and changes sign at large steps for most forward
!> methods: its order is fitted on the last four points of the sweep (the asymptotic regime;
!> the fit over the whole window on `# order-norm`), and a tolerance counts as reached where
!> the error falls below it and stays below. Output, per problem and method:
!>   itp-norm problem=NAME method=M order=P ffts_to_1e-8=N seconds_to_1e-8=S
!> with `# sweep-norm`, `# tol-norm`, `# summary-norm` and `# check-norm` lines as above, and
!> `# summary-best` lines comparing each method with the better of its two estimators.
!> Usage: fsym_itp_bench [--quick] [problem ...]
program fsym_itp_bench
    use, intrinsic :: iso_fortran_env, only: int64, output_unit
    use fsym_kinds, only: wp, ik
    use fsym_itp, only: fsym_itp_t
    use fsym_itp_problems, only: fsym_itp_problem
    implicit none
    integer, parameter :: nmeth = 13, maxpts = 40, ntol = 3
    real(wp), parameter :: tols(ntol) = [1.0e-8_wp, 1.0e-10_wp, 1.0e-12_wp]
    character(len=8), parameter :: meths(nmeth) = [character(len=8) :: 'CN', 'Strang', 'A', &
                                                    'C', 'A4', 'A5', 'A6', 'MP4', 'MP6', &
                                                    'MP8', 'A-MP6', 'TVT', 'B']
    character(len=8), parameter :: probs(3) = [character(len=8) :: 'ho3d', 'pt1d', 'gp3d']
    logical :: quick, want(3)
    real(wp) :: tol_stop = 1.0e-12_wp
    integer :: i, nargs
    character(len=64) :: arg

    quick = .false.
    want = .false.
    nargs = command_argument_count()
    do i = 1, nargs
        call get_command_argument(i, arg)
        if (arg == '--quick') then
            quick = .true.
        else if (any(probs == arg)) then
            want(findloc(probs, arg, dim=1)) = .true.
        else
            write (output_unit, '(a)') 'usage: fsym_itp_bench [--quick] [ho3d|pt1d|gp3d ...]'
            stop 2
        end if
    end do
    if (.not. any(want)) want = .true.
    do i = 1, 3
        if (want(i)) call problem(trim(probs(i)))
    end do
    if (want(3)) call gp_convergence()

contains

    subroutine setup(name, n, box, v, dv, psi0, g, exact, tend)
        character(len=*), intent(in) :: name
        integer, allocatable, intent(out) :: n(:)
        real(wp), allocatable, intent(out) :: box(:), v(:), dv(:, :), psi0(:)
        real(wp), intent(out) :: g, exact, tend
        real(wp) :: side
        call fsym_itp_problem(name, n, side, v, dv, psi0, g, exact)
        box = spread(side, 1, size(n))
        tend = 16.0_wp
    end subroutine setup

    !> Relative <H> error `err` and relative norm-decay energy error `errn` after t = tend at
    !> step tau (`sgnn` the sign of e_norm - exact); FFTs done. For gp3d the norm decay gives
    !> the chemical potential and is compared with the reference mu (`reference_gp`).
    subroutine one_run(name, meth, tau, err, nfft, ok, errn, sgnn)
        character(len=*), intent(in) :: name, meth
        real(wp), intent(in) :: tau
        real(wp), intent(out) :: err
        integer(ik), intent(out) :: nfft
        logical, intent(out) :: ok
        real(wp), intent(out), optional :: errn, sgnn
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend, exactn
        integer :: st
        character(len=256) :: msg
        call setup(name, n, box, v, dv, psi0, g, exact, tend)
        exactn = exact
        if (name == 'gp3d') call reference_gp(exact, exactn)
        msg = ''
        call p%init(n, box, v, meth, tau, st, msg, dv=dv, g=g)
        ok = st == 0
        if (.not. ok) then
            write (output_unit, '(5a)') '# problem=', name, ' method=', meth, ': '//trim(msg)
            return
        end if
        call p%set_state(1, psi0)
        call p%run(nint(tend / tau), st, msg, check=.false.)
        ok = st == 0
        if (.not. ok) then
            write (output_unit, '(5a)') '# problem=', name, ' method=', meth, ': '//trim(msg)
            return
        end if
        nfft = p%grid%nfft
        err = abs(p%energy(1) - exact) / abs(exact)
        if (present(errn)) errn = abs(p%e_norm(1) - exactn) / abs(exactn)
        if (present(sgnn)) sgnn = sign(1.0_wp, p%e_norm(1) - exactn)
        call p%destroy()
    end subroutine one_run

    !> The Gross-Pitaevskii energy `e` of gp3d converged in tau (A5, tau = 0.005) and, from
    !> the same state psi (norm one), its chemical potential mu = <T + V + g psi^2>
    !> = e + (g/2) int psi^4, the limit tau -> 0 of the norm-decay energy `e_norm` (the
    !> library holds V + g rho over a step, rho of the normalised state at the step's start,
    !> so at the fixed point e_norm is the eigenvalue of the step of H[rho]); computed once.
    subroutine reference_gp(e, mu)
        real(wp), intent(out) :: e, mu
        real(wp), save :: cached = 0.0_wp, cached_mu = 0.0_wp
        logical, save :: done = .false.
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:), psi(:)
        real(wp) :: g, exact, tend, nrm2
        integer :: st
        character(len=256) :: msg
        if (.not. done) then
            call setup('gp3d', n, box, v, dv, psi0, g, exact, tend)
            call p%init(n, box, v, 'A5', 0.005_wp, st, msg, dv=dv, g=g)
            call p%set_state(1, psi0)
            call p%run(nint(tend / 0.005_wp), st, msg, check=.false.)
            cached = p%energy(1)
            allocate (psi(size(psi0)))
            call p%get_state(1, psi)
            nrm2 = sum(psi**2) * p%grid%dvol
            cached_mu = cached + 0.5_wp * g * sum(psi**4) * p%grid%dvol / nrm2**2
            call p%resolved(1, st, msg)
            if (st /= 0) write (output_unit, '(2a)') '# gp3d reference: ', trim(msg)
            write (output_unit, '(a,es24.16,a)') '# gp3d reference energy (A5, tau = 0.005) ', &
                cached, trim(merge(' (resolved) ', ' (see above)', st == 0))
            write (output_unit, '(a,es24.16,a,es24.16,a,es9.2)') '# gp3d reference mu = '// &
                '<T + V + g psi^2> (same state) ', cached_mu, ' ; its e_norm ', p%e_norm(1), &
                ' rel_diff ', abs(p%e_norm(1) - cached_mu) / abs(cached_mu)
            done = .true.
            call p%destroy()
        end if
        e = cached
        mu = cached_mu
    end subroutine reference_gp

    !> The Gross-Pitaevskii iteration at large steps: relative <H> error of gp3d after t = 8,
    !> 16, 32, 64 for A and MP6 at tau = 1.6, 0.8, 0.4 (the density is held over each step, an
    !> explicit iteration in the density: converged, slow or oscillating?).
    subroutine gp_convergence()
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend, e(4), taus(3), mu
        character(len=8), parameter :: mm(2) = [character(len=8) :: 'A', 'MP6']
        integer :: st, j, k, i
        taus = [1.6_wp, 0.8_wp, 0.4_wp]
        call setup('gp3d', n, box, v, dv, psi0, g, exact, tend)
        call reference_gp(exact, mu)
        do k = 1, 2
            do i = 1, 3
                call p%init(n, box, v, trim(mm(k)), taus(i), st, dv=dv, g=g)
                if (st /= 0) cycle
                call p%set_state(1, psi0)
                do j = 1, 4
                    call p%run(nint(8.0_wp * 2**max(j - 2, 0) / taus(i)), st, check=.false.)
                    e(j) = abs(p%energy(1) - exact) / abs(exact)
                end do
                write (output_unit, '(3a,f4.2,a,4es10.2)') '# gpconv problem=gp3d method=', &
                    trim(mm(k)), ' tau=', taus(i), ' rel_err_at_t=8,16,32,64:', e
                call p%destroy()
            end do
        end do
    end subroutine gp_convergence

    !> Seconds per step of each method (min over interleaved repetitions) and the spread.
    subroutine timing(name, tpp, spread)
        character(len=*), intent(in) :: name
        real(wp), intent(out) :: tpp(nmeth), spread(nmeth)
        type(fsym_itp_t) :: p(nmeth)
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend, tmin(nmeth), tmax(nmeth), t
        integer :: st, m, r, nblock, reps
        integer(int64) :: c0, c1, rate
        logical :: ok(nmeth)
        call setup(name, n, box, v, dv, psi0, g, exact, tend)
        nblock = 20
        reps = 7
        if (size(n) == 1) nblock = 400
        do m = 1, nmeth
            call p(m)%init(n, box, v, trim(meths(m)), 0.1_wp, st, dv=dv, g=g)
            ok(m) = st == 0
            if (ok(m)) call p(m)%set_state(1, psi0)
        end do
        tmin = huge(1.0_wp)
        tmax = 0.0_wp
        do r = 1, reps
            do m = 1, nmeth
                if (.not. ok(m)) cycle
                call system_clock(c0, rate)
                call p(m)%run(nblock, st, check=.false.)
                call system_clock(c1)
                t = real(c1 - c0, wp) / real(rate, wp) / nblock
                tmin(m) = min(tmin(m), t)
                tmax(m) = max(tmax(m), t)
            end do
        end do
        tpp = tmin
        spread = (tmax - tmin) / tmin
        do m = 1, nmeth
            call p(m)%destroy()
        end do
    end subroutine timing

    subroutine problem(name)
        character(len=*), intent(in) :: name
        real(wp) :: taus(maxpts), errs(maxpts), errn(maxpts), sgn(maxpts), tpp(nmeth)
        real(wp) :: spread(nmeth), tau, tol_stop_n, eabs, e_gp
        logical :: res_r(ntol, nmeth, 3)
        real(wp) :: res_fft(ntol, nmeth, 3), res_sec(ntol, nmeth, 3), res_steps(nmeth, 2)
        logical :: res_x(ntol, nmeth, 3)
        integer(ik) :: nffts(maxpts), budget, budget_n
        integer :: m, k, np, nph, npn, fps
        logical :: ok, extrap, extrap_n
        type(fsym_itp_t) :: probe
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend
        integer :: st

        call setup(name, n, box, v, dv, psi0, g, exact, tend)
        eabs = abs(exact)   ! the norm-decay energy's limit: E0, for gp3d mu
        if (name == 'gp3d') then
            call reference_gp(e_gp, eabs)
            eabs = abs(eabs)
        end if
        call timing(name, tpp, spread)
        budget = 20000_ik   ! FFTs of one run
        if (size(n) == 1) budget = 1000000_ik
        ! the norm-decay energy's sweeps go on after the <H> sweep's end (Strang and CN need
        ! small steps: their values are extrapolated with the fitted order beyond the cap):
        ! --quick stops them at 1e-9 and caps 3-D runs at 10000 FFTs, the full run at 1e-12
        ! and 50000 FFTs (1-D: 1e6 and 5e6)
        budget_n = budget / 2
        if (size(n) == 1) budget_n = budget
        tol_stop_n = 1.0e-9_wp
        if (.not. quick) budget = 20 * budget
        if (.not. quick) budget_n = 5 * budget_n
        if (.not. quick) tol_stop_n = 1.0e-12_wp
        if (quick) tol_stop = 1.0e-10_wp
        do m = 1, nmeth
            tau = 3.2_wp
            if (meths(m) == 'Strang') tau = 0.4_wp
            if (meths(m) == 'CN') tau = 0.05_wp
            ! one sweep gives both estimators: the <H> sweep stops as before (its points
            ! 1..nph), the sweep goes on for the norm-decay energy (points 1..npn)
            np = 0
            nph = 0
            npn = 0
            extrap = .false.
            extrap_n = .false.
            do k = 1, maxpts
                call one_run(name, trim(meths(m)), tau, errs(k), nffts(k), ok, errn(k), sgn(k))
                if (.not. ok .and. np == 0) then   ! too large a first step: go on smaller
                    tau = tau / sqrt(2.0_wp)
                    cycle
                end if
                if (.not. ok) exit
                np = np + 1
                errs(np) = errs(k)
                errn(np) = errn(k)
                sgn(np) = sgn(k)
                nffts(np) = nffts(k)
                taus(np) = tau
                if (nph == 0) write (output_unit, '(5a,es10.3,a,es10.3,a,i0)') &
                    '# sweep problem=', name, ' method=', trim(meths(m)), ' tau=', tau, &
                    ' rel_err=', errs(np), ' ffts=', nffts(np)
                if (npn == 0) write (output_unit, '(5a,es10.3,a,es10.3,a,i0,a,sp,i2)') &
                    '# sweep-norm problem=', name, ' method=', trim(meths(m)), ' tau=', tau, &
                    ' rel_err=', errn(np), ' ffts=', nffts(np), ' sign=', nint(sgn(np))
                if (nph == 0) then   ! the <H> sweep's stopping rule, unchanged
                    if (errs(np) < 1.0e-13_wp) then
                        nph = np
                    else if (errs(np) < tol_stop .and. count(errs(1:np) < 1.0e-2_wp) >= 3) then
                        nph = np
                    else if (sqrt(2.0_wp) * nffts(np) > budget) then
                        nph = np
                        extrap = .true.
                    end if
                end if
                if (npn == 0) then   ! the same rule for the norm-decay energy
                    if (errn(np) < floor_n(tau, eabs)) then
                        ! at the rounding floor of e_norm: this point is noise, not kept
                        npn = np - 1
                        write (output_unit, '(5a,es10.3,a)') '# problem=', name, ' method=', &
                            trim(meths(m)), ': norm sweep stopped at tau=', tau, &
                            ', error below the rounding floor 10 eps/(tau |E|)'
                    else if (errn(np) < 1.0e-13_wp) then
                        npn = np
                    else if (errn(np) < tol_stop_n .and. &
                             count(errn(1:np) < 1.0e-2_wp) >= 3) then
                        npn = np
                    else if (sqrt(2.0_wp) * nffts(np) > budget_n) then
                        npn = np
                        extrap_n = .true.
                    end if
                end if
                if (nph > 0 .and. npn > 0) exit
                tau = tau / sqrt(2.0_wp)
            end do
            if (nph == 0) nph = np
            if (npn == 0) npn = np
            npn = max(npn, 1)
            call probe%init(n, box, v, trim(meths(m)), 0.1_wp, st, dv=dv, g=g)
            fps = probe%fft_per_step
            call probe%destroy()
            call analyse(name, m, 1, taus(1:nph), errs(1:nph), extrap, fps, tpp(m), &
                         spread(m), tend, eabs, res_fft(:, m, 1), res_sec(:, m, 1), &
                         res_steps(m, 1), res_x(:, m, 1), res_r(:, m, 1))
            call analyse(name, m, 2, taus(1:npn), errn(1:npn), extrap_n, fps, tpp(m), &
                         spread(m), tend, eabs, res_fft(:, m, 2), res_sec(:, m, 2), &
                         res_steps(m, 2), res_x(:, m, 2), res_r(:, m, 2))
            flush (output_unit)
        end do
        call summary(name, 1, res_fft(:, :, 1), res_sec(:, :, 1), res_x(:, :, 1), &
                     res_r(:, :, 1))
        call summary(name, 2, res_fft(:, :, 2), res_sec(:, :, 2), res_x(:, :, 2), &
                     res_r(:, :, 2))
        ! each method with the better of its two estimators (per tolerance; a norm value
        ! below the rounding floor does not count): for CN on the linear problems that is the
        ! norm-decay energy, for the others <H>
        do m = 1, nmeth
            do k = 1, ntol
                if (res_fft(k, m, 2) < res_fft(k, m, 1) .and. .not. res_r(k, m, 2)) then
                    res_fft(k, m, 3) = res_fft(k, m, 2)
                    res_sec(k, m, 3) = res_sec(k, m, 2)
                    res_x(k, m, 3) = res_x(k, m, 2)
                    res_r(k, m, 3) = res_r(k, m, 2)
                else
                    res_fft(k, m, 3) = res_fft(k, m, 1)
                    res_sec(k, m, 3) = res_sec(k, m, 1)
                    res_x(k, m, 3) = res_x(k, m, 1)
                    res_r(k, m, 3) = res_r(k, m, 1)
                end if
            end do
        end do
        call summary(name, 3, res_fft(:, :, 3), res_sec(:, :, 3), res_x(:, :, 3), &
                     res_r(:, :, 3))
        call check(name, 1, res_fft(:, :, 1), res_steps(:, 1), res_x(:, :, 1), tend)
        call check(name, 2, res_fft(:, :, 2), res_steps(:, 2), res_x(:, :, 2), tend)
    end subroutine problem

    !> Fitted order, FFTs and seconds to each tolerance of method m from its sweep, for the
    !> estimator `est` (1 <H>: the `itp` line; 2 the norm-decay energy: `itp-norm`).
    !> `res_r`: the norm-decay energy would need a step at which its rounding floor
    !> (`floor_n`) is above the tolerance: not reachable in double precision.
    subroutine analyse(name, m, est, taus, errs, extrap_in, fps, tpp, spread, tend, eabs, &
                       res_fft, res_sec, res_steps, res_x, res_r)
        character(len=*), intent(in) :: name
        integer, intent(in) :: m, est, fps
        real(wp), intent(in) :: taus(:), errs(:), tpp, spread, tend, eabs
        logical, intent(in) :: extrap_in
        real(wp), intent(out) :: res_fft(ntol), res_sec(ntol), res_steps
        logical, intent(out) :: res_x(ntol), res_r(ntol)
        real(wp) :: x(maxpts), y(maxpts), order, steps, order_all
        integer :: i, nfit, np, it
        logical :: extrap, stay
        character(len=5) :: sfx
        sfx = suffix(est)
        np = size(taus)
        res_fft(:) = huge(1.0_wp)
        res_sec(:) = huge(1.0_wp)
        res_steps = 1.0_wp
        res_x(:) = .true.
        res_r(:) = .false.
        if (np == 0) return
        ! fitted order: points with 1e-13 < err < 1e-2
        nfit = 0
        do i = 1, np
            if (errs(i) > 1.0e-13_wp .and. errs(i) < 1.0e-2_wp) then
                nfit = nfit + 1
                x(nfit) = log(taus(i))
                y(nfit) = log(errs(i))
            end if
        end do
        order = slope(x(1:nfit), y(1:nfit))
        stay = est == 2
        if (est == 2) then
            ! the norm-decay energy is not variational: its error changes sign at large steps
            ! for most forward methods (a zero crossing, pre-asymptotic), which pulls a fit
            ! over the whole sweep below the method's order. Its order is fitted on the last
            ! four points of that window (the smallest steps, the asymptotic regime); the fit
            ! over the whole window is printed on a # line. A tolerance counts as reached
            ! where the error falls below it and stays below (not at a dip by a crossing).
            order_all = order
            order = slope(x(max(1, nfit - 3):nfit), y(max(1, nfit - 3):nfit))
            write (output_unit, '(5a,f0.2,a,f0.2,a,i0)') '# order-norm problem=', name, &
                ' method=', trim(meths(m)), ' order_last4=', order, ' order_all=', &
                order_all, ' points=', nfit
        end if
        extrap = extrap_in
        steps = steps_at(1.0e-8_wp, taus, errs, order, tend, extrap, stay)
        if (extrap) write (output_unit, '(5a)') '# problem=', name, ' method=', &
            trim(meths(m)), ': '//trim(merge('value     ', 'norm value', est == 1))// &
            ' at 1e-8 extrapolated with the fitted order'
        if (est == 1) write (output_unit, '(5a,es9.2,a,i0)') '# timing problem=', name, &
            ' method=', trim(meths(m)), ' spread=', spread, ' ffts_per_step=', fps
        write (output_unit, '(7a,f0.2,a,i0,a,es10.3)') 'itp', trim(sfx), ' problem=', name, &
            ' method=', trim(meths(m)), ' order=', order, ' ffts_to_1e-8=', &
            nint(steps * fps, int64), ' seconds_to_1e-8=', steps * tpp
        res_fft(1) = steps * fps
        res_sec(1) = steps * tpp
        res_steps = steps
        res_x(1) = extrap
        if (est == 2) res_r(1) = floor_n(tend / steps, eabs) > tols(1)
        do it = 2, ntol   ! tighter tolerances, # lines
            steps = steps_at(tols(it), taus, errs, order, tend, extrap, stay)
            res_fft(it) = steps * fps
            res_sec(it) = steps * tpp
            res_x(it) = extrap
            if (est == 2) res_r(it) = floor_n(tend / steps, eabs) > tols(it)
            write (output_unit, '(7a,es8.1,a,i0,a,es10.3,a,l1)') '# tol', trim(sfx), &
                ' problem=', name, ' method=', trim(meths(m)), ' tol=', tols(it), ' ffts=', &
                nint(steps * fps, int64), ' seconds=', steps * tpp, ' extrapolated=', extrap
        end do
        do it = 1, ntol
            if (res_r(it)) write (output_unit, '(5a,es8.1,a)') '# problem=', name, &
                ' method=', trim(meths(m)), ': norm value at ', tols(it), &
                ' needs a step where the rounding floor of e_norm is above it'// &
                ' (not reachable in double precision)'
        end do
    end subroutine analyse

    !> The baselines: the cheaper Strang form (V/2 T V/2 or T/2 V T/2), and CN; the best
    !> forward method (order >= 4) by FFTs and by time, at each tolerance (`# summary`,
    !> `# summary-norm` for the norm-decay energy, `# summary-best` each method with the
    !> better of its two estimators).
    subroutine summary(name, est, res_fft, res_sec, res_x, res_r)
        character(len=*), intent(in) :: name
        integer, intent(in) :: est
        real(wp), intent(in) :: res_fft(ntol, nmeth), res_sec(ntol, nmeth)
        logical, intent(in) :: res_x(ntol, nmeth), res_r(ntol, nmeth)
        logical :: base(nmeth), fwd(nmeth)
        integer :: it, i, k, ib, m
        base = [(any(meths(m) == ['Strang', 'TVT   ']), m = 1, nmeth)]
        fwd = [(.not. (base(m) .or. meths(m) == 'CN'), m = 1, nmeth)]
        do it = 1, ntol
            i = minloc(res_fft(it, :), mask=fwd, dim=1)
            k = minloc(res_sec(it, :), mask=fwd, dim=1)
            ib = minloc(res_fft(it, :), mask=base, dim=1)
            write (output_unit, '(5a,es8.1,a,i0,5a,i0,a,f0.1,a,f0.1,3a,f0.1,a,f0.1,a,l1,a,l1)') &
                '# summary', trim(suffix(est)), ' problem=', name, &
                ' tol=', tols(it), ' strang_ffts=', &
                nint(res_fft(it, ib), int64), ' (', trim(meths(ib)), ') best_forward_ffts=', &
                trim(meths(i)), ':', nint(res_fft(it, i), int64), ' ratio_strang=', &
                res_fft(it, ib) / res_fft(it, i), ' ratio_cn=', res_fft(it, 1) / res_fft(it, i), &
                ' best_forward_time=', trim(meths(k)), ' time_ratio_strang=', &
                minval(res_sec(it, :), mask=base) / res_sec(it, k), ' time_ratio_cn=', &
                res_sec(it, 1) / res_sec(it, k), ' extrapolated=', &
                res_x(it, i) .or. res_x(it, ib) .or. res_x(it, k), ' cn_extrapolated=', &
                res_x(it, 1)
            if (est /= 1 .and. any(res_r(it, :))) write (output_unit, '(5a,es8.1,a,3l1)') &
                '# summary', trim(suffix(est)), ' problem=', name, ' tol=', tols(it), &
                ' below the rounding floor of e_norm (strang, best, cn): ', &
                res_r(it, ib), res_r(it, i) .or. res_r(it, k), res_r(it, 1)
        end do
    end subroutine summary

    !> Check of the interpolation at 1e-8: the best forward method and the cheaper Strang
    !> run with the next whole number of steps above the interpolated one (`# check`; for the
    !> norm-decay energy `# check-norm`, only where the value was interpolated, not
    !> extrapolated beyond the sweep).
    subroutine check(name, est, res_fft, res_steps, res_x, tend)
        character(len=*), intent(in) :: name
        integer, intent(in) :: est
        real(wp), intent(in) :: res_fft(ntol, nmeth), res_steps(nmeth), tend
        logical, intent(in) :: res_x(ntol, nmeth)
        logical :: base(nmeth), fwd(nmeth), ok
        integer :: i, ib, m, k
        real(wp) :: err, errn
        integer(ik) :: nfft
        base = [(any(meths(m) == ['Strang', 'TVT   ']), m = 1, nmeth)]
        fwd = [(.not. (base(m) .or. meths(m) == 'CN'), m = 1, nmeth)]
        i = minloc(res_fft(1, :), mask=fwd, dim=1)
        ib = minloc(res_fft(1, :), mask=base, dim=1)
        do m = 1, nmeth
            if (m /= i .and. m /= ib) cycle
            if (est == 2 .and. res_x(1, m)) cycle
            k = ceiling(res_steps(m) - 1.0e-9_wp)
            call one_run(name, trim(meths(m)), tend / k, err, nfft, ok, errn)
            if (est == 2) err = errn
            if (ok) write (output_unit, '(7a,i0,a,es10.3,a,es10.3,a,i0)') '# check', &
                trim(suffix(est)), ' problem=', &
                name, ' method=', trim(meths(m)), ' steps=', k, ' tau=', tend / k, &
                ' rel_err=', err, ' ffts=', nfft
        end do
    end subroutine check

    !> Suffix of the output lines of estimator est: <H> none, 2 `-norm`, 3 `-best`.
    pure character(len=5) function suffix(est)
        integer, intent(in) :: est
        select case (est)
        case (1)
            suffix = ''
        case (2)
            suffix = '-norm'
        case default
            suffix = '-best'
        end select
    end function suffix

    !> Rounding floor of the relative error of the norm-decay energy at step tau:
    !> e_norm = -ln(norm)/tau takes the rounding of ln(norm) (a few eps) divided by tau;
    !> 10 eps/(tau |E|) with a margin (measured on pt1d: CN's error stops falling near
    !> 0.4 eps/(tau |E|)).
    pure real(wp) function floor_n(tau, eabs)
        real(wp), intent(in) :: tau, eabs
        floor_n = 10.0_wp * epsilon(1.0_wp) / (tau * eabs)
    end function floor_n

    !> Least-squares slope of y against x (0 for fewer than two points).
    pure real(wp) function slope(x, y) result(order)
        real(wp), intent(in) :: x(:), y(:)
        integer :: nfit
        nfit = size(x)
        order = 0.0_wp
        if (nfit >= 2) order = sum((x - sum(x) / nfit) * (y - sum(y) / nfit)) / &
                               sum((x - sum(x) / nfit)**2)
    end function slope

    !> Steps (of t = tend) at which the error reaches tol: log-log interpolation between the
    !> sweep points around it, else extrapolation with the fitted order (`extrap` true). With
    !> `stay` the crossing is the last one: the first point from which every smaller step has
    !> an error below tol.
    real(wp) function steps_at(tol, taus, errs, order, tend, extrap, stay) result(steps)
        real(wp), intent(in) :: tol, taus(:), errs(:), order, tend
        logical, intent(out) :: extrap
        logical, intent(in), optional :: stay
        integer :: k, np
        real(wp) :: f, lt
        np = size(taus)
        extrap = .false.
        k = findloc(errs < tol, .true., dim=1)
        if (present(stay)) then
            if (stay) then
                k = findloc(errs >= tol, .true., dim=1, back=.true.) + 1
                if (k > np) k = 0
            end if
        end if
        if (k >= 2) then
            f = (log(tol) - log(errs(k - 1))) / (log(errs(k)) - log(errs(k - 1)))
            lt = log(taus(k - 1)) + f * (log(taus(k)) - log(taus(k - 1)))
        else if (k == 1) then
            lt = log(taus(1)) + (log(tol) - log(errs(1))) / max(order, 1.0_wp)
            extrap = .true.
        else
            lt = log(taus(np)) + (log(tol) - log(errs(np))) / max(order, 0.5_wp)
            extrap = .true.
        end if
        steps = tend / exp(lt)
    end function steps_at

end program fsym_itp_bench
