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

    !> Relative <H> error after t = tend at step tau; FFTs done.
    subroutine one_run(name, meth, tau, err, nfft, ok)
        character(len=*), intent(in) :: name, meth
        real(wp), intent(in) :: tau
        real(wp), intent(out) :: err
        integer(ik), intent(out) :: nfft
        logical, intent(out) :: ok
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend
        integer :: st
        character(len=256) :: msg
        call setup(name, n, box, v, dv, psi0, g, exact, tend)
        if (name == 'gp3d') exact = reference_gp()
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
        call p%destroy()
    end subroutine one_run

    !> The Gross-Pitaevskii energy of gp3d converged in tau (A5, tau = 0.005), computed once.
    real(wp) function reference_gp() result(e)
        real(wp), save :: cached = 0.0_wp
        logical, save :: done = .false.
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend
        integer :: st
        character(len=256) :: msg
        if (.not. done) then
            call setup('gp3d', n, box, v, dv, psi0, g, exact, tend)
            call p%init(n, box, v, 'A5', 0.005_wp, st, msg, dv=dv, g=g)
            call p%set_state(1, psi0)
            call p%run(nint(tend / 0.005_wp), st, msg, check=.false.)
            cached = p%energy(1)
            call p%resolved(1, st, msg)
            if (st /= 0) write (output_unit, '(2a)') '# gp3d reference: ', trim(msg)
            write (output_unit, '(a,es24.16,a)') '# gp3d reference energy (A5, tau = 0.005) ', &
                cached, trim(merge(' (resolved) ', ' (see above)', st == 0))
            done = .true.
            call p%destroy()
        end if
        e = cached
    end function reference_gp

    !> The Gross-Pitaevskii iteration at large steps: relative <H> error of gp3d after t = 8,
    !> 16, 32, 64 for A and MP6 at tau = 1.6, 0.8, 0.4 (the density is held over each step, an
    !> explicit iteration in the density: converged, slow or oscillating?).
    subroutine gp_convergence()
        type(fsym_itp_t) :: p
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend, e(4), taus(3)
        character(len=8), parameter :: mm(2) = [character(len=8) :: 'A', 'MP6']
        integer :: st, j, k, i
        taus = [1.6_wp, 0.8_wp, 0.4_wp]
        call setup('gp3d', n, box, v, dv, psi0, g, exact, tend)
        exact = reference_gp()
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
        real(wp) :: taus(maxpts), errs(maxpts), tpp(nmeth), spread(nmeth), tau, order
        real(wp) :: x(maxpts), y(maxpts), steps, res_fft(ntol, nmeth), res_sec(ntol, nmeth)
        real(wp) :: res_steps(nmeth)
        logical :: base(nmeth), fwd(nmeth), res_x(ntol, nmeth)
        integer :: it, ib
        integer(ik) :: nffts(maxpts), budget
        integer :: m, k, np, i, nfit, fps
        logical :: ok, extrap
        type(fsym_itp_t) :: probe
        integer, allocatable :: n(:)
        real(wp), allocatable :: box(:), v(:), dv(:, :), psi0(:)
        real(wp) :: g, exact, tend
        integer :: st

        call setup(name, n, box, v, dv, psi0, g, exact, tend)
        call timing(name, tpp, spread)
        budget = 20000_ik   ! FFTs of one run
        if (size(n) == 1) budget = 1000000_ik
        if (.not. quick) budget = 20 * budget
        if (quick) tol_stop = 1.0e-10_wp
        do m = 1, nmeth
            tau = 3.2_wp
            if (meths(m) == 'Strang') tau = 0.4_wp
            if (meths(m) == 'CN') tau = 0.05_wp
            np = 0
            extrap = .false.
            do k = 1, maxpts
                call one_run(name, trim(meths(m)), tau, errs(k), nffts(k), ok)
                if (.not. ok .and. np == 0) then   ! too large a first step: go on smaller
                    tau = tau / sqrt(2.0_wp)
                    cycle
                end if
                if (.not. ok) exit
                np = np + 1
                errs(np) = errs(k)
                nffts(np) = nffts(k)
                taus(np) = tau
                write (output_unit, '(5a,es10.3,a,es10.3,a,i0)') '# sweep problem=', name, &
                    ' method=', trim(meths(m)), ' tau=', tau, ' rel_err=', errs(np), &
                    ' ffts=', nffts(np)
                if (errs(np) < 1.0e-13_wp) exit
                if (errs(np) < tol_stop .and. count(errs(1:np) < 1.0e-2_wp) >= 3) exit
                if (sqrt(2.0_wp) * nffts(np) > budget) then   ! the next point would exceed it
                    extrap = .true.
                    exit
                end if
                tau = tau / sqrt(2.0_wp)
            end do
            res_fft(:, m) = huge(1.0_wp)
            res_sec(:, m) = huge(1.0_wp)
            res_steps(m) = 1.0_wp
            res_x(:, m) = .true.
            if (np == 0) cycle
            ! fitted order: points with 1e-13 < err < 1e-2
            nfit = 0
            do i = 1, np
                if (errs(i) > 1.0e-13_wp .and. errs(i) < 1.0e-2_wp) then
                    nfit = nfit + 1
                    x(nfit) = log(taus(i))
                    y(nfit) = log(errs(i))
                end if
            end do
            order = 0.0_wp
            if (nfit >= 2) order = sum((x(1:nfit) - sum(x(1:nfit)) / nfit) * &
                                       (y(1:nfit) - sum(y(1:nfit)) / nfit)) / &
                                   sum((x(1:nfit) - sum(x(1:nfit)) / nfit)**2)
            call probe%init(n, box, v, trim(meths(m)), 0.1_wp, st, dv=dv, g=g)
            fps = probe%fft_per_step
            call probe%destroy()
            steps = steps_at(1.0e-8_wp, taus(1:np), errs(1:np), order, tend, extrap)
            if (extrap) write (output_unit, '(5a)') '# problem=', name, ' method=', &
                trim(meths(m)), ': value at 1e-8 extrapolated with the fitted order'
            write (output_unit, '(5a,es9.2,a,i0)') '# timing problem=', name, ' method=', &
                trim(meths(m)), ' spread=', spread(m), ' ffts_per_step=', fps
            write (output_unit, '(5a,f0.2,a,i0,a,es10.3)') 'itp problem=', name, ' method=', &
                trim(meths(m)), ' order=', order, ' ffts_to_1e-8=', nint(steps * fps, int64), &
                ' seconds_to_1e-8=', steps * tpp(m)
            res_fft(1, m) = steps * fps
            res_sec(1, m) = steps * tpp(m)
            res_steps(m) = steps
            res_x(1, m) = extrap
            do it = 2, ntol   ! tighter tolerances, # lines
                steps = steps_at(tols(it), taus(1:np), errs(1:np), order, tend, extrap)
                res_fft(it, m) = steps * fps
                res_sec(it, m) = steps * tpp(m)
                res_x(it, m) = extrap
                write (output_unit, '(5a,es8.1,a,i0,a,es10.3,a,l1)') '# tol problem=', name, &
                    ' method=', trim(meths(m)), ' tol=', tols(it), ' ffts=', &
                    nint(steps * fps, int64), ' seconds=', steps * tpp(m), ' extrapolated=', &
                    extrap
            end do
            flush (output_unit)
        end do
        ! the baselines: the cheaper Strang form (V/2 T V/2 or T/2 V T/2), and CN; the best
        ! forward method (order >= 4) by FFTs and by time, at each tolerance
        base = [(any(meths(m) == ['Strang', 'TVT   ']), m = 1, nmeth)]
        fwd = [(.not. (base(m) .or. meths(m) == 'CN'), m = 1, nmeth)]
        do it = 1, ntol
            i = minloc(res_fft(it, :), mask=fwd, dim=1)
            k = minloc(res_sec(it, :), mask=fwd, dim=1)
            ib = minloc(res_fft(it, :), mask=base, dim=1)
            write (output_unit, '(3a,es8.1,a,i0,5a,i0,a,f0.1,a,f0.1,3a,f0.1,a,f0.1,a,l1,a,l1)') &
                '# summary problem=', name, ' tol=', tols(it), ' strang_ffts=', &
                nint(res_fft(it, ib), int64), ' (', trim(meths(ib)), ') best_forward_ffts=', &
                trim(meths(i)), ':', nint(res_fft(it, i), int64), ' ratio_strang=', &
                res_fft(it, ib) / res_fft(it, i), ' ratio_cn=', res_fft(it, 1) / res_fft(it, i), &
                ' best_forward_time=', trim(meths(k)), ' time_ratio_strang=', &
                minval(res_sec(it, :), mask=base) / res_sec(it, k), ' time_ratio_cn=', &
                res_sec(it, 1) / res_sec(it, k), ' extrapolated=', &
                res_x(it, i) .or. res_x(it, ib) .or. res_x(it, k), ' cn_extrapolated=', &
                res_x(it, 1)
        end do
        ! check of the interpolation at 1e-8: the best forward method and the cheaper Strang
        ! run with the next whole number of steps above the interpolated one
        i = minloc(res_fft(1, :), mask=fwd, dim=1)
        ib = minloc(res_fft(1, :), mask=base, dim=1)
        do m = 1, nmeth
            if (m /= i .and. m /= ib) cycle
            k = ceiling(res_steps(m) - 1.0e-9_wp)
            call one_run(name, trim(meths(m)), tend / k, errs(1), nffts(1), ok)
            if (ok) write (output_unit, '(5a,i0,a,es10.3,a,es10.3,a,i0)') '# check problem=', &
                name, ' method=', trim(meths(m)), ' steps=', k, ' tau=', tend / k, &
                ' rel_err=', errs(1), ' ffts=', nffts(1)
        end do
    end subroutine problem

    !> Steps (of t = tend) at which the error reaches tol: log-log interpolation between the
    !> sweep points around it, else extrapolation with the fitted order (`extrap` true).
    real(wp) function steps_at(tol, taus, errs, order, tend, extrap) result(steps)
        real(wp), intent(in) :: tol, taus(:), errs(:), order, tend
        logical, intent(out) :: extrap
        integer :: k, np
        real(wp) :: f, lt
        np = size(taus)
        extrap = .false.
        k = findloc(errs < tol, .true., dim=1)
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
