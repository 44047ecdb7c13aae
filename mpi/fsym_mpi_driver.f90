!> Driver of the distributed N-body model: every rank integrates its block of bodies with the
!> library's `integrator_t` on `mpi_nbody_model_t`.
!>
!>     mpirun -np P fsym_mpi_driver [n=1000] [method=A] [steps=5] [h=1e-3] [blocks=even|uneven]
!>         [check=1] [state=FILE] [reps=R] [fail_rank=r fail_at=k]
!>
!> - `check=1`: rank 0 also runs the serial model (`nbody_model_t`, all bodies, no MPI) and
!>   prints `mpi: bitwise identical to serial` or the first difference (exit status 1);
!> - `state=FILE`: rank 0 writes the gathered end state (raw doubles, q then v);
!> - `reps=R`: time the run R times (from the same start) and print the minimum and the
!>   spread of the seconds per step, with the messages and bytes per step of rank 0;
!> - `fail_rank`, `fail_at`: that rank's force fails at its k-th evaluation; prints whether
!>   every rank returned the failure with its state intact (exit status 1 if not).
program fsym_mpi_driver
    use mpi_f08
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use fsym
    use fsym_nbody, only: nbody_model_t
    use fsym_mpi_nbody, only: mpi_nbody_model_t
    use fsym_mpi_driver_models, only: failing_model_t
    !$ use omp_lib, only: omp_get_max_threads
    use fsym_scale_setup, only: scale_initial_state, scale_counts, scale_write_state, &
                                scale_difference, scale_arg_int, scale_arg_real, scale_arg_text, &
                                SCALE_EPS
    implicit none
    class(mpi_nbody_model_t), allocatable :: model
    type(integrator_t) :: integ
    real(wp), allocatable :: q(:, :), v(:, :), m(:), ql(:, :), vl(:, :), q0(:, :), v0(:, :)
    real(wp), allocatable :: qe(:, :), ve(:, :), tstep(:)
    integer, allocatable :: counts(:), displs(:)
    character(len=32) :: method, blocks
    character(len=256) :: statefile, msg, diff
    integer :: ierr, rank, nranks, n, nsteps, reps, failr, faila, st, k, r, nl, nthreads
    integer :: failed_at, ok_local, ok_all, provided
    integer(int64) :: g0, r0
    real(wp) :: h, t0
    logical :: check, uneven

    ! threads (OpenMP inside the pair kernel) never call MPI: the funneled level suffices
    call MPI_Init_thread(MPI_THREAD_FUNNELED, provided, ierr)
    call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
    n = scale_arg_int('n', 1000)
    nsteps = scale_arg_int('steps', 5)
    reps = scale_arg_int('reps', 0)
    h = scale_arg_real('h', 1.0e-3_wp)
    failr = scale_arg_int('fail_rank', -1)
    faila = scale_arg_int('fail_at', 0)
    check = scale_arg_int('check', 0) /= 0
    call scale_arg_text('method', 'A', method)
    call scale_arg_text('blocks', 'even', blocks)
    call scale_arg_text('state', '', statefile)
    uneven = blocks == 'uneven'
    nthreads = 1
    !$ nthreads = omp_get_max_threads()

    allocate (q(3, n), v(3, n), m(n), counts(nranks), displs(nranks))
    call scale_initial_state(n, q, v, m)
    call scale_counts(n, nranks, uneven, counts)
    if (failr >= 0) then
        allocate (failing_model_t :: model)
        select type (model)
        type is (failing_model_t)
            model%fail_rank = failr
            model%fail_at = faila
        end select
    else
        allocate (mpi_nbody_model_t :: model)
    end if
    msg = ''
    call model%init(MPI_COMM_WORLD, m, 1.0_wp, SCALE_EPS, counts, st, msg)
    if (st /= FSYM_SUCCESS) call fail_all('init: '//trim(msg))
    nl = model%local_size()
    ql = q(:, model%first:model%last)
    vl = v(:, model%first:model%last)
    call integ%init_by_name(trim(method), model, 3, nl, st, msg)
    if (st /= FSYM_SUCCESS) call fail_all('integrator: '//trim(msg))

    if (failr >= 0) then
        ! step until a step fails; the state must be that of before the step, on every rank
        failed_at = 0
        do k = 1, nsteps
            q0 = ql
            v0 = vl
            call integ%step(model, ql, vl, h, st, msg)
            if (st /= FSYM_SUCCESS) then
                failed_at = k
                exit
            end if
        end do
        ok_local = 0
        if (failed_at > 0) then   ! nested: each comparison is made (same is not pure)
            if (same(ql, q0)) then
                if (same(vl, v0)) ok_local = failed_at
            end if
        end if
        call MPI_Allreduce(ok_local, ok_all, 1, MPI_INTEGER, MPI_MIN, MPI_COMM_WORLD, ierr)
        k = ok_all
        call MPI_Allreduce(ok_local, ok_all, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD, ierr)
        if (rank == 0) then
            if (k > 0 .and. k == ok_all) then
                write (output_unit, '(a,i0,a,i0,a,i0,a)') 'mpi: failure on rank ', failr, &
                    ' propagated: all ', nranks, ' ranks returned a failure at step ', k, &
                    ' with the state intact'
            else
                write (output_unit, '(a)') 'mpi: failure NOT propagated cleanly'
            end if
        end if
        call model%destroy()
        call MPI_Finalize(ierr)
        if (k == 0 .or. k /= ok_all) error stop 1
        stop
    end if

    if (reps > 0) then
        allocate (tstep(reps))
        do r = 1, reps
            ql = q(:, model%first:model%last)
            vl = v(:, model%first:model%last)
            call integ%init_by_name(trim(method), model, 3, nl, st, msg)
            g0 = model%gathers
            r0 = model%reductions
            call MPI_Barrier(MPI_COMM_WORLD, ierr)
            t0 = MPI_Wtime()
            call integ%run(model, ql, vl, h, int(nsteps, ik), st, msg)
            call MPI_Barrier(MPI_COMM_WORLD, ierr)
            tstep(r) = (MPI_Wtime() - t0) / real(nsteps, wp)
            if (st /= FSYM_SUCCESS) call fail_all('run: '//trim(msg))
        end do
        if (rank == 0) write (output_unit, '(a,i0,a,a,a,i0,a,i0,a,f0.3,a,f0.2,a,2(f0.2,a),i0)') &
            'step N=', n, ' method=', trim(method), ' ranks=', nranks, ' threads=', nthreads, &
            ' us/step=', 1.0e6_wp * minval(tstep), ' spread%=', &
            100.0_wp * (maxval(tstep) / minval(tstep) - 1.0_wp), ' gathers/step=', &
            real(model%gathers - g0, wp) / nsteps, ' reductions/step=', &
            real(model%reductions - r0, wp) / nsteps, ' local_bodies=', nl
    else
        call integ%run(model, ql, vl, h, int(nsteps, ik), st, msg)
        if (st /= FSYM_SUCCESS) call fail_all('run: '//trim(msg))
    end if

    ! gather the end state on rank 0
    allocate (qe(3, n), ve(3, n))
    displs(1) = 0
    do r = 2, nranks
        displs(r) = displs(r - 1) + 3 * counts(r - 1)
    end do
    call MPI_Gatherv(ql, 3 * nl, MPI_DOUBLE_PRECISION, qe, 3 * counts, displs, &
                     MPI_DOUBLE_PRECISION, 0, MPI_COMM_WORLD, ierr)
    call MPI_Gatherv(vl, 3 * nl, MPI_DOUBLE_PRECISION, ve, 3 * counts, displs, &
                     MPI_DOUBLE_PRECISION, 0, MPI_COMM_WORLD, ierr)
    k = 0
    if (rank == 0) then
        if (len_trim(statefile) > 0) then
            call scale_write_state(trim(statefile), qe, ve, st)
            if (st /= FSYM_SUCCESS) then
                write (error_unit, '(a)') 'cannot write '//trim(statefile)
                k = 1
            end if
        end if
        if (check) then
            call serial_run(diff)
            if (len_trim(diff) == 0) then
                write (output_unit, '(a,i0,a,a,a)') 'mpi: bitwise identical to serial (', &
                    nranks, ' ranks, ', trim(blocks), ' blocks)'
            else
                write (output_unit, '(a)') 'mpi: first difference from serial at '//trim(diff)
                k = 1
            end if
        end if
    end if
    call MPI_Bcast(k, 1, MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
    call model%destroy()
    call MPI_Finalize(ierr)
    if (k /= 0) error stop 1

contains

    !> The serial reference: `nbody_model_t` on all bodies, same method, steps and start.
    subroutine serial_run(text)
        character(len=*), intent(out) :: text  !! '' or the first difference
        type(nbody_model_t) :: smodel
        type(integrator_t) :: sinteg
        real(wp), allocatable :: qs(:, :), vs(:, :)
        integer :: sst
        allocate (qs, source=q)
        allocate (vs, source=v)
        call smodel%init(m, 1.0_wp, SCALE_EPS, sst)
        call sinteg%init_by_name(trim(method), smodel, 3, n, sst)
        call sinteg%run(smodel, qs, vs, h, int(nsteps, ik), sst)
        if (sst /= FSYM_SUCCESS) then
            text = 'the serial run failed'
            return
        end if
        call scale_difference(qs, vs, qe, ve, text)
    end subroutine serial_run

    !> Whether two arrays hold the same bits.
    logical function same(x, y)
        real(wp), intent(in) :: x(:, :)  !! first
        real(wp), intent(in) :: y(:, :)  !! second
        character(len=256) :: t
        call scale_difference(x, x, y, y, t)
        same = len_trim(t) == 0
    end function same

    !> Print a message on rank 0 and end every rank with a failure.
    subroutine fail_all(text)
        character(len=*), intent(in) :: text  !! what went wrong
        integer :: e
        if (rank == 0) write (error_unit, '(a)') 'fsym_mpi_driver: '//text
        call MPI_Abort(MPI_COMM_WORLD, 1, e)
    end subroutine fail_all

end program fsym_mpi_driver
