!> Engine benchmarks, printed as markdown: (1) the library's step against hand-written inlined
!> loops of the same methods on the paper's Kepler orbit, (2) an ensemble of n independent
!> Kepler orbits (ns per particle-force), (3) a direct-summation N-body force (time per step
!> and the share of the step spent outside the force), (4) resident memory over a long run.
!>
!> Usage: fsym-bench [all|overhead|ensemble|nbody|memory|steps] [nsteps]
!>   `memory NSTEPS` runs FR on the paper orbit for NSTEPS steps and prints VmRSS/VmHWM at
!>   checkpoints 0, 1e3, 1e4, ...; `steps NSTEPS` the same run without checkpoints (for
!>   valgrind heap counts: run it with two different NSTEPS, compare the allocations).
program fsym_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_handloops, only: hand_fr, hand_a, hand_c, hand_a6, hand_bm, hand_fr_n
    use fsym_nbody_bench, only: bench_nbody
    use fsym_timing, only: seconds_since, median
    implicit none

    !> The Kepler model seen through an extension type: `integrator_t%step` then takes the
    !> general path (reverse communication, type-bound force), as for any user model.
    type, extends(kepler_model_t) :: general_kepler_t
    end type general_kepler_t

    character(len=32) :: what, arg
    integer(ik) :: nmem

    what = 'all'
    if (command_argument_count() >= 1) call get_command_argument(1, what)
    nmem = 10000000_ik
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg)
        read (arg, *) nmem
    end if
    select case (trim(what))
    case ('overhead')
        call bench_overhead()
    case ('ensemble')
        call bench_ensemble()
    case ('nbody')
        call bench_nbody()
    case ('memory')
        call bench_memory(nmem, .true.)
    case ('steps')
        call bench_memory(nmem, .false.)
    case default
        call bench_overhead()
        call bench_ensemble()
        call bench_nbody()
    end select

contains

    !> Library against the hand loop: FR, A, C, A6, BM at eps = P/1000.
    subroutine bench_overhead()
        character(len=4), parameter :: names(5) = [character(len=4) :: 'FR', 'A', 'C', 'A6', 'BM']
        integer, parameter :: nrep = 7
        integer(ik), parameter :: nsteps = 1000000_ik
        type(integrator_t) :: integ
        type(kepler_model_t) :: model
        type(general_kepler_t) :: general
        type(scheme_t) :: s
        real(wp) :: q0(2), v0(2), period, h, q(2, 1), v(2, 1), qh(2), vh(2), qrun(2), qstep(2)
        real(wp) :: trun(nrep), tstep(nrep), thand(nrep), tgen(nrep), tr, ts, th, tg, nfe, dq
        integer(int64) :: t0
        integer :: m, r, st

        call kepler_paper_orbit(q0, v0, period)
        h = period / 1000.0_wp
        write (output_unit, '(a)') '## Engine overhead: library against a hand-written loop', ''
        write (output_unit, '(a,i0,a,i0,a)') 'Paper orbit (e = 0.9), eps = P/1000, ', nsteps, &
            ' steps per run, median of ', nrep, ' runs, all on one body (d = 2, n = 1).'// &
            ' `run` = one call `integrator_t%run(model, q, v, h, nsteps)` with'// &
            ' `kepler_model_t` (the kernel''s Kepler path takes every step without returning);'// &
            ' `step` = a loop of `integrator_t%step` calls, one per step (the same path, one'// &
            ' call and its checks per step); general = the loop of `step` with an extension of'// &
            ' `kepler_model_t` (reverse communication, type-bound force, as for any user'// &
            ' model); hand = hand-written inlined loop (app/fsym_handloops.f90).'// &
            ' `nF` = force + gradient evaluations per step (a gradient counted as one).'// &
            ' `abs(dq)` = max difference of the end positions of `run` and of `step` against'// &
            ' the hand loop.'
        write (output_unit, '(a)') '', &
            '| method | nF/step | run ns/step | step ns/step | general ns/step | hand ns/step |'// &
            ' run ns/eval | hand ns/eval | ratio run/hand | ratio step/hand | '// &
            'ratio general/hand | abs(dq) |', '|---|---|---|---|---|---|---|---|---|---|---|---|'
        do m = 1, size(names)
            call fsym_scheme_by_name(names(m), s)
            call integ%init(s, model, 2, 1, st)
            do r = 1, nrep
                call timed_steps(integ, s, model, q0, v0, h, nsteps, .true., q, v, trun(r))
                qrun = q(:, 1)
                nfe = real(integ%force_evaluations() + integ%gradient_evaluations(), wp) / &
                      real(nsteps, wp)
                call timed_steps(integ, s, model, q0, v0, h, nsteps, .false., q, v, tstep(r))
                qstep = q(:, 1)
                call timed_steps(integ, s, general, q0, v0, h, nsteps, .false., q, v, tgen(r))
                ! hand loop
                qh = q0; vh = v0
                call system_clock(t0)
                select case (trim(names(m)))
                case ('FR')
                    call hand_fr(s%c, h, nsteps, qh, vh)
                case ('A')
                    call hand_a(s%c, s%u, h, nsteps, qh, vh)
                case ('C')
                    call hand_c(s%c, s%u, h, nsteps, qh, vh)
                case ('A6')
                    call hand_a6(s%c, s%u, h, nsteps, qh, vh)
                case default
                    call hand_bm(s%c, h, nsteps, qh, vh)
                end select
                thand(r) = seconds_since(t0)
            end do
            dq = max(maxval(abs(qrun - qh)), maxval(abs(qstep - qh)))
            tr = median(trun) / real(nsteps, wp) * 1.0e9_wp
            ts = median(tstep) / real(nsteps, wp) * 1.0e9_wp
            th = median(thand) / real(nsteps, wp) * 1.0e9_wp
            tg = median(tgen) / real(nsteps, wp) * 1.0e9_wp
            write (output_unit, '(a,f0.3,6(a,f0.2),3(a,f0.3),a,es9.2,a)') &
                '| '//trim(names(m))//' | ', nfe, ' | ', tr, ' | ', ts, ' | ', tg, ' | ', th, &
                ' | ', tr / nfe, ' | ', th / nfe, ' | ', tr / th, ' | ', ts / th, ' | ', &
                tg / th, ' | ', dq, ' |'
        end do
        write (output_unit, '(a)') ''

    end subroutine bench_overhead

    !> nsteps library steps of scheme s with `mdl` from (q0, v0), in one `run` call or in
    !> a loop of `step` calls; their time t.
    subroutine timed_steps(integ, s, mdl, q0, v0, h, nsteps, one_call, q, v, t)
        type(integrator_t), intent(inout) :: integ
        type(scheme_t), intent(in) :: s
        class(force_model_t), intent(inout) :: mdl
        real(wp), intent(in) :: q0(2), v0(2), h
        integer(ik), intent(in) :: nsteps
        logical, intent(in) :: one_call
        real(wp), intent(out) :: q(2, 1), v(2, 1), t
        integer(int64) :: t0
        integer(ik) :: k
        call integ%init(s, mdl, 2, 1)
        q(:, 1) = q0; v(:, 1) = v0
        call system_clock(t0)
        if (one_call) then
            call integ%run(mdl, q, v, h, nsteps)
        else
            do k = 1, nsteps
                call integ%step(mdl, q, v, h)
            end do
        end if
        t = seconds_since(t0)
    end subroutine timed_steps

    !> n independent Kepler orbits in one state array: ns per particle-force for the force
    !> alone, for a whole library FR step, and for the hand-written FR loop over the bodies.
    subroutine bench_ensemble()
        integer, parameter :: ns(5) = [1, 10, 100, 1000, 10000]
        integer, parameter :: nrep = 7
        type(kepler_model_t) :: model
        type(integrator_t) :: integ
        type(scheme_t) :: s
        real(wp), allocatable :: q(:, :), v(:, :), a(:, :), q0(:, :), v0(:, :)
        real(wp) :: period, h, tf(nrep), ts(nrep), tr(nrep), th(nrep), e, sink, per
        integer(int64) :: t0
        integer :: i, j, n, r, st, mst
        integer(ik) :: k, nloop, nstep

        write (output_unit, '(a)') '## Ensemble of n independent Kepler orbits', ''
        write (output_unit, '(a)') 'Each column of q(2, n) an orbit of eccentricity 0.5..0.9;'// &
            ' force = `kepler_model_t%acceleration` on the whole array; library step ='// &
            ' a loop of `integrator_t%step` with FR (3 forces per step) at eps = P/1000;'// &
            ' library run = the same steps in one `integrator_t%run` call; hand = the'// &
            ' hand-written FR loop over the bodies. About 2e7 particle-forces per run, median'// &
            ' of 7. ns per particle-force = time / (forces x n).', '', &
            '| n | force only | library FR step | library FR run | hand FR loop | '// &
            'ratio step/hand | ratio run/hand |', '|---|---|---|---|---|---|---|'
        call fsym_scheme_by_name('FR', s)
        sink = 0.0_wp
        do i = 1, size(ns)
            n = ns(i)
            allocate (q(2, n), v(2, n), a(2, n), q0(2, n), v0(2, n))
            do j = 1, n
                e = 0.5_wp + 0.4_wp * real(j - 1, wp) / real(max(n - 1, 1), wp)
                call kepler_elliptic_orbit(e, q0(:, j), v0(:, j), period)
            end do
            h = period / 1000.0_wp
            nloop = max(1_ik, 20000000_ik / n)
            nstep = max(1_ik, nloop / 3)
            q = q0; v = v0
            call integ%init(s, model, 2, n, st)
            do r = 1, nrep
                call system_clock(t0)
                do k = 1, nloop
                    mst = 0
                    call model%acceleration(q, a, mst)
                end do
                tf(r) = seconds_since(t0)
                sink = sink + a(1, n)
                q = q0; v = v0
                call system_clock(t0)
                do k = 1, nstep
                    call integ%step(model, q, v, h)
                end do
                ts(r) = seconds_since(t0)
                q = q0; v = v0
                call system_clock(t0)
                call integ%run(model, q, v, h, nstep)
                tr(r) = seconds_since(t0)
                q = q0; v = v0
                call system_clock(t0)
                call hand_fr_n(s%c, h, nstep, n, q, v)
                th(r) = seconds_since(t0)
                sink = sink + q(1, n)
            end do
            per = 1.0e9_wp / real(3_ik * nstep * n, wp)
            write (output_unit, '(a,i0,6(a,f0.3),a)') '| ', n, ' | ', &
                median(tf) / real(nloop * n, wp) * 1.0e9_wp, ' | ', median(ts) * per, ' | ', &
                median(tr) * per, ' | ', median(th) * per, ' | ', median(ts) / median(th), &
                ' | ', median(tr) / median(th), ' |'
            deallocate (q, v, a, q0, v0)
        end do
        if (sink == 1.0_wp) write (output_unit, '(a)') '.'
        write (output_unit, '(a)') ''
    end subroutine bench_ensemble

    !> Resident memory while FR (Kepler path), C' (general path) and RKN each run nsteps
    !> steps one `step` call at a time, then FR nsteps steps in one `run` call (Linux
    !> /proc/self/status).
    subroutine bench_memory(nsteps, checkpoints)
        integer(ik), intent(in) :: nsteps
        logical, intent(in) :: checkpoints
        type(integrator_t) :: integ, integ2, integ3
        type(kepler_model_t) :: model
        type(general_kepler_t) :: general
        class(stepper_t), allocatable :: rkn
        real(wp) :: q(2, 1), v(2, 1), q2(2, 1), v2(2, 1), q3(2, 1), v3(2, 1), q4(2, 1), v4(2, 1)
        real(wp) :: period, h
        integer(ik) :: k, next
        integer :: st
        call kepler_paper_orbit(q(:, 1), v(:, 1), period)
        q2 = q; v2 = v; q3 = q; v3 = v
        h = period / 1000.0_wp
        call integ%init_by_name('FR', model, 2, 1, st)        ! Kepler path
        call integ2%init_by_name('C''', general, 2, 1, st)    ! general path, extrapolated
        call fsym_new_stepper('RKN', model, 2, 1, rkn, st)
        if (checkpoints) call print_mem(0_ik)
        next = 1000_ik
        do k = 1, nsteps
            call integ%step(model, q, v, h, st)
            call integ2%step(general, q2, v2, h, st)
            call rkn%step(model, q3, v3, h, st)
            if (checkpoints .and. (k == next .or. k == nsteps)) then
                call print_mem(k)
            end if
            if (k == next) next = next * 10_ik
        end do
        ! and the same number of FR steps in one run call
        call integ3%init_by_name('FR', model, 2, 1, st)
        call kepler_paper_orbit(q4(:, 1), v4(:, 1), period)
        call integ3%run(model, q4, v4, h, nsteps, st)
        if (checkpoints) call print_mem(nsteps)
        write (output_unit, '(a,i0,a,4es12.4)') 'steps ', integ%steps(), &
            ' of FR (Kepler path), C'' (general path), RKN and FR in one run call; energies ', &
            kepler_energy(q(:, 1), v(:, 1)), kepler_energy(q2(:, 1), v2(:, 1)), &
            kepler_energy(q3(:, 1), v3(:, 1)), kepler_energy(q4(:, 1), v4(:, 1))
    end subroutine bench_memory

    !> Print VmRSS and VmHWM of this process.
    subroutine print_mem(k)
        integer(ik), intent(in) :: k
        character(len=128) :: line, rss, hwm
        integer :: u, ios
        rss = '?'; hwm = '?'
        open (newunit=u, file='/proc/self/status', action='read', status='old', iostat=ios)
        if (ios /= 0) return
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, 'VmRSS:') == 1) rss = adjustl(line(7:))
            if (index(line, 'VmHWM:') == 1) hwm = adjustl(line(7:))
        end do
        close (u)
        write (output_unit, '(a,i0,a)') 'after ', k, ' steps: VmRSS '//trim(rss)// &
            ', VmHWM '//trim(hwm)
    end subroutine print_mem

end program fsym_bench
