!> Engine benchmarks, printed as markdown: (1) ratios of the library against hand-written
!> loops (FR, A, C, A6, BM; d = 2, 3; n = 1, 1000; the built-in Kepler model and a user's
!> model), (2) a direct-summation N-body force (time per step and the share of the step
!> spent outside the force), (3) resident memory over a long run, (4) the cost of the
!> kernel's kinds of update loop and of two forms of a force loop on this machine.
!>
!> Usage: fsym-bench [all|ratios|loops|nbody|memory|steps] [nsteps or repetitions]
!>   `ratios [NREP]` the ratio lines (NREP repetitions, default 21); `loops [NREP]` the
!>   loop lines; `all [NREP]` ratios and loops with NREP repetitions, then the N-body table;
!>   `memory NSTEPS` runs FR on the paper orbit for NSTEPS steps and prints VmRSS/VmHWM at
!>   checkpoints 0, 1e3, 1e4, ...; `steps NSTEPS` the same run without checkpoints (for
!>   valgrind heap counts: run it with two different NSTEPS, compare the allocations).
program fsym_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym_exit, only: fsym_exit_failure
    use fsym
    use fsym_bench_models, only: user_kepler_t
    use fsym_bench_ratios, only: bench_ratios
    use fsym_nbody_bench, only: bench_nbody
    use fsym_bench_loops, only: bench_loops
    implicit none

    character(len=32) :: what, arg
    integer(ik) :: nmem
    integer :: ios

    what = 'all'
    if (command_argument_count() >= 1) call get_command_argument(1, what)
    nmem = 10000000_ik
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg)
        read (arg, *, iostat=ios) nmem
        if (ios /= 0) call fsym_exit_failure('fsym-bench', &
                                             'the second argument does not read: '//trim(arg), 2)
    end if
    select case (trim(what))
    case ('ratios')
        if (command_argument_count() < 2) nmem = 21
        call bench_ratios(int(max(1_ik, min(nmem, 1000_ik))))
    case ('nbody')
        call bench_nbody()
    case ('loops')
        if (command_argument_count() < 2) nmem = 21
        call bench_loops(int(max(1_ik, min(nmem, 1000_ik))))
    case ('memory')
        call bench_memory(nmem, .true.)
    case ('steps')
        call bench_memory(nmem, .false.)
    case default
        if (command_argument_count() < 2) nmem = 21
        call bench_ratios(int(max(1_ik, min(nmem, 1000_ik))))
        call bench_loops(int(max(1_ik, min(nmem, 1000_ik))))
        call bench_nbody()
    end select

contains

    !> Resident memory while FR (built-in model), C' (a user's model) and RKN each run nsteps
    !> steps one `step` call at a time, then FR nsteps steps in one `run` call (Linux
    !> /proc/self/status).
    subroutine bench_memory(nsteps, checkpoints)
        integer(ik), intent(in) :: nsteps
        logical, intent(in) :: checkpoints
        type(integrator_t) :: integ, integ2, integ3
        type(kepler_model_t) :: model
        type(user_kepler_t) :: general
        class(stepper_t), allocatable :: rkn
        real(wp) :: q(2, 1), v(2, 1), q2(2, 1), v2(2, 1), q3(2, 1), v3(2, 1), q4(2, 1), v4(2, 1)
        real(wp) :: period, h
        integer(ik) :: k, next
        integer :: st
        call kepler_paper_orbit(q(:, 1), v(:, 1), period)
        q2 = q; v2 = v; q3 = q; v3 = v
        h = period / 1000.0_wp
        call integ%init_by_name('FR', model, 2, 1, st)        ! built-in model
        call integ2%init_by_name('C''', general, 2, 1, st)    ! user's model, extrapolated
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
            ' of FR (built-in model), C'' (user model), RKN and FR in one run call; energies ', &
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
