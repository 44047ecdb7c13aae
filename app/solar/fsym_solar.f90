!> The outer solar system (Hairer, Lubich, Wanner) over 500 000 days with FR, A, A', C, A6 and
!> BM at several steps: phase-space error against the reference state in the data file, max
!> relative energy error, force and gradient evaluations, run time. Writes an HDF5 file
!> (default `out/solar.h5`, checked writable before the work, written through a temporary
!> name); scripts/report_solar.py renders doc/solar-system.md from it.
!>
!> Usage: fsym-solar [options] [data-file [hdf5-file]]
!>   --checkpoint-every N  write a checkpoint every N steps (HDF5, atomic; default: none)
!>   --checkpoint FILE     its file (default out/solar.ckpt.h5)
!>   --resume FILE         go on from a checkpoint: bitwise the run that was interrupted
!>   --end-states FILE     write the end states and counts as hex images (for bitwise tests)
program fsym_solar
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_solar_data, only: solar_data_t, read_solar_data
    use fsym_solar_output, only: solar_results_t, write_solar_h5
    use fsym_checkpoint_h5, only: fsym_ckpt_h5_write, fsym_ckpt_h5_read
    use fsym_h5, only: fsym_rename_file, fsym_check_writable, fsym_exit_failure, &
                       fsym_temp_name, fsym_remove_file
    implicit none
    character(len=4), parameter :: methods(6) = [character(len=4) :: 'FR', 'A', 'A''', 'C', &
                                                 'A6', 'BM']
    real(wp), parameter :: steps(6) = [100.0_wp, 50.0_wp, 20.0_wp, 10.0_wp, 5.0_wp, 2.0_wp]
    character(len=512) :: data_path, h5_path
    character(len=256) :: msg
    type(solar_data_t) :: dat
    type(solar_results_t) :: res
    type(nbody_model_t) :: model
    type(integrator_t) :: it
    real(wp), allocatable :: q(:, :), v(:, :)
    real(wp) :: e0, de
    integer(int64) :: t0, t1, rate, ticks
    integer :: km, kh, k, nstep, st, k1, every, npos, ia
    character(len=512) :: ckpt_path, resume_path, ends_path, arg
    real(wp), allocatable :: ck(:), prog(:), packed(:)
    logical :: resuming

    data_path = 'data/outer_solar_system.txt'
    h5_path = 'out/solar.h5'
    ckpt_path = 'out/solar.ckpt.h5'
    resume_path = ''
    ends_path = ''
    every = 0
    npos = 0
    ia = 0
    do while (ia < command_argument_count())
        ia = ia + 1
        call get_command_argument(ia, arg)
        select case (arg)
        case ('--checkpoint-every', '--checkpoint', '--resume', '--end-states')
            if (ia == command_argument_count()) call fail(trim(arg)//' needs a value')
            ia = ia + 1
            if (arg == '--checkpoint-every') then
                call get_command_argument(ia, arg)
                read (arg, *, iostat=st) every
                if (st /= 0 .or. every < 1) call fail('--checkpoint-every needs N >= 1')
            else if (arg == '--checkpoint') then
                call get_command_argument(ia, ckpt_path)
            else if (arg == '--resume') then
                call get_command_argument(ia, resume_path)
            else
                call get_command_argument(ia, ends_path)
            end if
        case default
            npos = npos + 1
            if (npos == 1) data_path = arg
            if (npos == 2) h5_path = arg
        end select
    end do

    ! every output is written through a temporary name and renamed: check them first
    call fsym_check_writable(trim(h5_path), st, msg)
    if (st /= 0) call fail(msg)
    if (every > 0) then
        call fsym_check_writable(trim(ckpt_path), st, msg)
        if (st /= 0) call fail(msg)
    end if
    if (len_trim(ends_path) > 0) then
        call fsym_check_writable(trim(ends_path), st, msg)
        if (st /= 0) call fail(msg)
    end if
    call read_solar_data(trim(data_path), dat, st, msg)
    if (st /= 0) call fail(msg)
    call model%init(dat%m, dat%g, stat=st, errmsg=msg)
    if (st /= 0) call fail(msg)
    e0 = model%energy(dat%q0, dat%v0)

    allocate (res%methods(size(methods)), res%h(size(steps)))
    res%methods = methods
    res%h = steps
    res%t_end = dat%t_end
    res%n = dat%n
    allocate (res%err_phase(size(methods), size(steps)), res%err_q(size(methods), size(steps)), &
              res%err_energy(size(methods), size(steps)), res%seconds(size(methods), size(steps)), &
              res%nforce(size(methods), size(steps)), res%ngrad(size(methods), size(steps)), &
              res%q_end(3, dat%n, size(methods), size(steps)), &
              res%v_end(3, dat%n, size(methods), size(steps)))
    res%q_ref = dat%qref
    res%v_ref = dat%vref
    call system_clock(count_rate=rate)
    resuming = len_trim(resume_path) > 0
    if (resuming) then
        call fsym_ckpt_h5_read(trim(resume_path), ck, prog, packed, st, msg)
        if (st /= 0) call fail(msg)
        if (size(prog) /= 5 .or. size(packed) /= size(pack_results())) then
            call fail('checkpoint '//trim(resume_path)//' is not of this run')
        end if
        if (.not. (prog(1) >= 1 .and. prog(1) <= size(methods) .and. prog(2) >= 1 .and. &
                   prog(2) <= size(steps) .and. prog(3) >= 1 .and. prog(3) < 1.0e9_wp)) then
            call fail('checkpoint '//trim(resume_path)//' refused: progress out of range')
        end if
        call unpack_results(packed)
    end if

    write (output_unit, '(a,i0,a,f0.0,a)') 'outer solar system: ', dat%n, ' bodies, ', &
        dat%t_end, ' days'
    write (output_unit, '(a6,a8,a14,a14,a14,a12,a10,a10)') 'method', 'h', 'phase err', &
        'max |dq|', 'max|dE/E|', 'F', 'G', 'seconds'
    do km = 1, size(methods)
        do kh = 1, size(steps)
            if (resuming) then      ! cases finished before the checkpoint: results restored
                if (km < nint(prog(1)) .or. (km == nint(prog(1)) .and. kh < nint(prog(2)))) cycle
            end if
            nstep = nint(dat%t_end / steps(kh))
            q = dat%q0; v = dat%v0
            call it%init_by_name(methods(km), model, 3, dat%n, st, msg)
            if (st /= 0) call fail(msg)
            de = 0.0_wp
            ticks = 0
            k1 = 1
            if (resuming) then
                call it%load_checkpoint(q, v, ck, st, msg)
                if (st /= 0) call fail(msg)
                k1 = nint(prog(3)) + 1; de = prog(4); ticks = int(prog(5), int64)
                resuming = .false.
            end if
            do k = k1, nstep
                call system_clock(t0)
                call it%step(model, q, v, steps(kh), st, msg)
                call system_clock(t1)
                ticks = ticks + (t1 - t0)
                if (st /= 0) call fail(msg)
                de = max(de, abs(model%energy(q, v) / e0 - 1.0_wp))
                if (every > 0 .and. k < nstep) then
                    if (mod(k, every) == 0) call save_checkpoint()
                end if
            end do
            res%err_phase(km, kh) = sqrt(sum((q - dat%qref)**2) + sum((v - dat%vref)**2))
            res%err_q(km, kh) = maxval(sqrt(sum((q - dat%qref)**2, dim=1)))
            res%err_energy(km, kh) = de
            res%nforce(km, kh) = it%force_evaluations()
            res%ngrad(km, kh) = it%gradient_evaluations()
            res%seconds(km, kh) = real(ticks, wp) / real(rate, wp)
            res%q_end(:, :, km, kh) = q
            res%v_end(:, :, km, kh) = v
            write (output_unit, '(a6,f8.1,3es14.4,2i12,f10.3)') trim(methods(km)), steps(kh), &
                res%err_phase(km, kh), res%err_q(km, kh), de, res%nforce(km, kh), &
                res%ngrad(km, kh), res%seconds(km, kh)
            flush (output_unit)
        end do
    end do

    if (len_trim(ends_path) > 0) call write_end_states(trim(ends_path))
    call write_solar_h5(trim(h5_path), trim(data_path), res, FSYM_VERSION, st, msg)
    if (st /= 0) then
        if (every > 0) call fail(trim(msg)//'; the last checkpoint '//trim(ckpt_path)// &
                                 ' is kept: free space and run again with --resume '// &
                                 trim(ckpt_path))
        call fail(msg)
    end if
    write (output_unit, '(a)') 'wrote '//trim(h5_path)

contains

    !> The checkpoint: the integrator's state, where the loops are, the results so far.
    subroutine save_checkpoint()
        if (allocated(ck)) deallocate (ck)
        allocate (ck(it%checkpoint_length()))
        call it%save_checkpoint(q, v, ck, st, msg)
        if (st /= 0) call fail(msg)
        call fsym_ckpt_h5_write(trim(ckpt_path), ck, &
                                [real(km, wp), real(kh, wp), real(k, wp), de, real(ticks, wp)], &
                                pack_results(), st, msg)
        if (st /= 0) call fail(msg)
    end subroutine save_checkpoint

    !> The results as one array (the order `unpack_results` reads).
    function pack_results() result(x)
        real(wp), allocatable :: x(:)
        x = [reshape(res%err_phase, [size(res%err_phase)]), &
             reshape(res%err_q, [size(res%err_q)]), &
             reshape(res%err_energy, [size(res%err_energy)]), &
             reshape(res%seconds, [size(res%seconds)]), &
             real(reshape(res%nforce, [size(res%nforce)]), wp), &
             real(reshape(res%ngrad, [size(res%ngrad)]), wp), &
             reshape(res%q_end, [size(res%q_end)]), reshape(res%v_end, [size(res%v_end)])]
    end function pack_results

    subroutine unpack_results(x)
        real(wp), intent(in) :: x(:)
        integer :: m, p
        m = size(res%err_phase); p = 0
        res%err_phase = reshape(x(p + 1:p + m), shape(res%err_phase)); p = p + m
        res%err_q = reshape(x(p + 1:p + m), shape(res%err_q)); p = p + m
        res%err_energy = reshape(x(p + 1:p + m), shape(res%err_energy)); p = p + m
        res%seconds = reshape(x(p + 1:p + m), shape(res%seconds)); p = p + m
        res%nforce = reshape(int(x(p + 1:p + m), int64), shape(res%nforce)); p = p + m
        res%ngrad = reshape(int(x(p + 1:p + m), int64), shape(res%ngrad)); p = p + m
        m = size(res%q_end)
        res%q_end = reshape(x(p + 1:p + m), shape(res%q_end)); p = p + m
        res%v_end = reshape(x(p + 1:p + m), shape(res%v_end))
    end subroutine unpack_results

    !> End states, energy errors and counts as hex images of their bits, one line per case
    !> (written to a temporary name, then renamed).
    subroutine write_end_states(path)
        character(len=*), intent(in) :: path
        integer :: u, ios, a, b
        character(len=:), allocatable :: tmp
        tmp = fsym_temp_name(path)
        open (newunit=u, file=tmp, action='write', status='replace', iostat=ios)
        if (ios /= 0) call fail('cannot write '//tmp)
        do a = 1, size(methods)
            do b = 1, size(steps)
                if (ios /= 0) exit
                write (u, '(a,1x,f0.1,1x,z16.16,2(1x,i0),*(1x,z16.16))', iostat=ios) &
                    trim(methods(a)), steps(b), transfer(res%err_energy(a, b), 0_int64), &
                    res%nforce(a, b), res%ngrad(a, b), &
                    transfer(res%q_end(:, :, a, b), [0_int64]), &
                    transfer(res%v_end(:, :, a, b), [0_int64])
            end do
        end do
        if (ios == 0) then
            close (u, iostat=ios)
        else
            close (u, status='delete', iostat=b)
            if (b /= 0) continue        ! removed below in any case
        end if
        if (ios /= 0) then
            call fsym_remove_file(tmp)
            call fail('cannot write '//path//' (disk full?); its temporary removed')
        end if
        call fsym_rename_file(tmp, path, st, msg)
        if (st /= 0) call fail(msg)
    end subroutine write_end_states

    !> Report and exit with status 1 (flushed, without the exit handlers: see
    !> `fsym_exit_failure`); every writer has removed its temporary before.
    subroutine fail(text)
        character(len=*), intent(in) :: text
        call fsym_exit_failure('fsym-solar', text)
    end subroutine fail

end program fsym_solar
