!> The outer solar system (Hairer, Lubich, Wanner) over 500 000 days with FR, A, A', C, A6 and
!> BM at several steps: phase-space error against the reference state in the data file, max
!> relative energy error, force and gradient evaluations, run time. Writes an HDF5 file
!> (default `out/solar.h5`, checked writable before the work, written through a temporary
!> name); scripts/report_solar.py renders doc/solar-system.md from it.
!>
!> Usage: fsym-solar [data-file [hdf5-file]]
program fsym_solar
    use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
    use fsym
    use fsym_solar_data, only: solar_data_t, read_solar_data
    use fsym_solar_output, only: solar_results_t, write_solar_h5
    use fsym_h5, only: fsym_check_writable
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
    integer :: km, kh, k, nstep, st

    data_path = 'data/outer_solar_system.txt'
    h5_path = 'out/solar.h5'
    if (command_argument_count() >= 1) call get_command_argument(1, data_path)
    if (command_argument_count() >= 2) call get_command_argument(2, h5_path)

    ! the output is written through a temporary name and renamed: check it first
    call fsym_check_writable(trim(h5_path), st, msg)
    if (st /= 0) call fail(msg)
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

    write (output_unit, '(a,i0,a,f0.0,a)') 'outer solar system: ', dat%n, ' bodies, ', &
        dat%t_end, ' days'
    write (output_unit, '(a6,a8,a14,a14,a14,a12,a10,a10)') 'method', 'h', 'phase err', &
        'max |dq|', 'max|dE/E|', 'F', 'G', 'seconds'
    do km = 1, size(methods)
        do kh = 1, size(steps)
            nstep = nint(dat%t_end / steps(kh))
            q = dat%q0; v = dat%v0
            call it%init_by_name(methods(km), model, 3, dat%n, st, msg)
            if (st /= 0) call fail(msg)
            de = 0.0_wp
            ticks = 0
            do k = 1, nstep
                call system_clock(t0)
                call it%step(model, q, v, steps(kh), st, msg)
                call system_clock(t1)
                ticks = ticks + (t1 - t0)
                if (st /= 0) call fail(msg)
                de = max(de, abs(model%energy(q, v) / e0 - 1.0_wp))
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

    call write_solar_h5(trim(h5_path), trim(data_path), res, FSYM_VERSION, st, msg)
    if (st /= 0) call fail(msg)
    write (output_unit, '(a)') 'wrote '//trim(h5_path)

contains

    subroutine fail(text)
        character(len=*), intent(in) :: text
        write (error_unit, '(a)') 'fsym-solar: '//trim(text)
        error stop 1
    end subroutine fail

end program fsym_solar
