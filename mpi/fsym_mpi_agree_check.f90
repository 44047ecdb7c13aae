!> Agreement of the ranks (issue 23): one rank differs from the others, and every rank must
!> return the same status, promptly (CTest gives each case a timeout of seconds: before the
!> agreement, `case=nan` hung in the model's gather).
!>
!>     mpirun -np P fsym_mpi_agree_check case=nan|model|h|label|method|none [rank=r]
!>
!> - `nan`: a NaN in rank r's velocities: FSYM_ERR_NONFINITE_STATE everywhere, nothing changed;
!> - `model`: rank r's force fails at its 3rd evaluation: FSYM_ERR_MODEL everywhere, every rank
!>   at the same step with the state of that step's start;
!> - `h`: rank r is given 2h: `init` fails with FSYM_ERR_BAD_STEP everywhere;
!> - `label`: rank r is given an unreadable label: FSYM_ERR_UNKNOWN_METHOD everywhere;
!> - `method`: rank r is given another (valid) method: FSYM_ERR_BAD_ARGUMENT everywhere;
!> - `none`: no rank differs: status 0 everywhere (the check can pass only when it should).
!> Prints one line on rank 0 and exits non-zero unless every rank got the expected status.
program fsym_mpi_agree_check
    use mpi_f08
    use, intrinsic :: iso_fortran_env, only: output_unit
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use fsym
    use fsym_mpi_agree, only: mpi_integrator_t
    use fsym_mpi_driver_models, only: failing_model_t
    use fsym_scale_setup, only: scale_initial_state, scale_counts, scale_arg_int, &
                                scale_arg_text, SCALE_EPS
    implicit none
    type(failing_model_t) :: model
    type(mpi_integrator_t) :: mi
    real(wp), allocatable :: q(:, :), v(:, :), m(:), ql(:, :), vl(:, :), q0(:, :), v0(:, :)
    integer, allocatable :: counts(:)
    character(len=16) :: what, label
    character(len=512) :: msg
    integer :: ierr, rank, nranks, n, odd, st, expect, ok, ok_all, nl, smin, smax
    real(wp) :: h

    call MPI_Init(ierr)
    call MPI_Comm_rank(MPI_COMM_WORLD, rank, ierr)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks, ierr)
    call scale_arg_text('case', 'none', what)
    odd = scale_arg_int('rank', nranks - 1)
    n = 24
    h = 1.0e-3_wp
    allocate (q(3, n), v(3, n), m(n), counts(nranks))
    call scale_initial_state(n, q, v, m)
    call scale_counts(n, nranks, .false., counts)
    if (what == 'model') then
        model%fail_rank = odd; model%fail_at = 3
    end if
    call model%init(MPI_COMM_WORLD, m, 1.0_wp, SCALE_EPS, counts, st, msg)
    nl = model%local_size()
    ql = q(:, model%first:model%last)
    vl = v(:, model%first:model%last)
    label = 'A'
    if (rank == odd .and. what == 'label') label = 'A7x(1'
    if (rank == odd .and. what == 'method') label = 'C'
    if (rank == odd .and. what == 'h') h = 2.0_wp * h
    if (rank == odd .and. what == 'nan') vl(2, 1) = ieee_value(1.0_wp, ieee_quiet_nan)
    q0 = ql; v0 = vl
    select case (what)
    case ('nan'); expect = FSYM_ERR_NONFINITE_STATE
    case ('model'); expect = FSYM_ERR_MODEL
    case ('h'); expect = FSYM_ERR_BAD_STEP
    case ('label'); expect = FSYM_ERR_UNKNOWN_METHOD
    case ('method'); expect = FSYM_ERR_BAD_ARGUMENT
    case default; expect = FSYM_SUCCESS
    end select

    msg = ''
    call mi%init(MPI_COMM_WORLD, trim(label), model, 3, nl, h, st, msg)
    if (st == FSYM_SUCCESS) call mi%run(model, ql, vl, 5_ik, st, msg)
    ok = 0
    if (st == expect) ok = 1
    if (what == 'nan' .or. what == 'h' .or. what == 'label' .or. what == 'method') then
        if (.not. (same(ql, q0) .and. same(vl, v0))) ok = 0         ! nothing changed
    end if
    ! every rank at the same step count
    call MPI_Allreduce(int(mi%it%steps()), smin, 1, MPI_INTEGER, MPI_MIN, MPI_COMM_WORLD, ierr)
    call MPI_Allreduce(int(mi%it%steps()), smax, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD, ierr)
    if (smin /= smax) ok = 0
    call MPI_Allreduce(ok, ok_all, 1, MPI_INTEGER, MPI_MIN, MPI_COMM_WORLD, ierr)
    if (rank == 0) write (output_unit, '(a,a,a,i0,a,i0,a,i0,a,i0,a,a)') 'mpi agree case=', &
        trim(what), ' ranks=', nranks, ' expected=', expect, ' steps=', smin, ' all ranks ', &
        ok_all, ': ', trim(msg)
    call mi%destroy()
    call model%destroy()
    call MPI_Finalize(ierr)
    if (ok_all /= 1) error stop 1

contains

    !> Whether two arrays hold the same bits (NaN included).
    logical function same(x, y)
        real(wp), intent(in) :: x(:, :), y(:, :)
        same = all(transfer(x, 1_ik, size(x)) == transfer(y, 1_ik, size(y)))
    end function same

end program fsym_mpi_agree_check
