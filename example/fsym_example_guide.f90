!> The program of the user guide (`doc/pages/guide.md`): a model of one's own
!> (`fsym_guide_model`), step / run / run_to, an observer, a checkpoint and its resumption, the
!> step-size guard, errors as status and message, and the two checkers of `fsym_checks`.
!> Each part is between `! [name]` markers that the guide quotes; its output is
!> doc/output/fsym_example_guide.txt (the test command compares them).
program fsym_example_guide
    use fsym
    use fsym_guide_model, only: plummer_model_t, energy_watch_t, plummer_energy
    implicit none
    integer, parameter :: n = 2
    type(plummer_model_t) :: model
    type(integrator_t) :: integ, again
    type(energy_watch_t) :: watch
    real(wp) :: q(3, n), v(3, n), q0(3, n), v0(3, n), q1(3, n), v1(3, n), h, e0
    real(wp), allocatable :: ck(:)
    real(wp) :: worst, order
    integer :: where(2), stat
    character(len=256) :: msg

    msg = ''
    ! [setup]
    model%mu = 1.0_wp
    model%eps = 0.05_wp
    ! two bodies on inclined, eccentric orbits around the centre (unit masses)
    q0(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]
    v0(:, 1) = [0.0_wp, 0.8_wp, 0.3_wp]
    q0(:, 2) = [0.0_wp, -2.0_wp, 0.5_wp]
    v0(:, 2) = [0.6_wp, 0.0_wp, 0.1_wp]
    q = q0; v = v0
    h = 0.01_wp
    call integ%init_by_name('A', model, 3, n, stat, msg)   ! d = 3 dimensions, n bodies
    if (stat /= FSYM_SUCCESS) error stop 'init'
    ! [setup]

    ! [step]
    e0 = plummer_energy(model, q, v)
    call integ%step(model, q, v, h, stat, msg)                 ! one step of h
    call integ%run(model, q, v, h, 99, stat, msg)              ! 99 more (int or int64 count)
    call integ%run_to(model, q, v, h, 2.505_wp, stat, msg)     ! whole steps, then one short one
    if (stat /= FSYM_SUCCESS) error stop 'run'
    write (*, '(a,f6.3,a,i0,a,i0,a,es9.2)') 'run_to: t = ', integ%time(), ', steps ', &
        integ%steps(), ', forces ', integ%force_evaluations(), ', |dE/E| = ', &
        abs(plummer_energy(model, q, v) / e0 - 1.0_wp)
    ! [step]

    ! [observe]
    watch%model = model
    watch%e0 = plummer_energy(model, q, v)
    call integ%run(model, q, v, h, 1000, stat, msg, observer=watch, every=100)
    write (*, '(a,i0,a,es9.2)') 'observer: called ', watch%calls, &
        ' times, worst |dE/E| = ', watch%worst
    ! [observe]

    ! [checkpoint]
    allocate (ck(integ%checkpoint_length()))
    call integ%save_checkpoint(q, v, ck, stat, msg)            ! the complete state, flat
    q1 = q; v1 = v
    call integ%run(model, q, v, h, 500, stat, msg)             ! goes on ...
    ! ... and elsewhere (another run of the program): the same method and shape, then load
    call again%init_by_name('A', model, 3, n, stat, msg)
    call again%load_checkpoint(q1, v1, ck, stat, msg)          ! q1, v1 and the clock restored
    call again%run(model, q1, v1, h, 500, stat, msg)
    write (*, '(a,l1,a,f6.3)') 'checkpoint: resumed run bitwise equal: ', &
        same_bits(q1, q) .and. same_bits(v1, v), ', t = ', again%time()
    ! [checkpoint]

    ! [guard]
    call integ%set_guard(model, .true., stat, msg)             ! on: refuse |h| omega > x*
    q1 = q; v1 = v
    call integ%step(model, q, v, 5.0_wp, stat, msg)            ! far too large: h omega > x*
    write (*, '(a,i0,a,l1)') 'guard: stat = ', stat, ' (FSYM_ERR_STEP_TOO_LARGE), state kept: ', &
        same_bits(q1, q)
    write (*, '(a)') '  '//trim(msg)
    call integ%step(model, q, v, h, stat, msg)                 ! a normal step still runs
    write (*, '(a,i0)') 'guard: a step of h = 0.01 gives stat = ', stat
    ! [guard]

    ! [errors]
    call again%init_by_name('A(2)', model, 3, n, stat, msg)    ! a label that cannot be read
    write (*, '(a,i0,a)') 'errors: stat = ', stat, ', '//trim(fsym_status_message(stat))
    write (*, '(a)') '  '//trim(msg)
    q1 = q
    q1(2, 2) = ieee_nan()
    call integ%step(model, q1, v, h, stat, msg)                ! a NaN in the state is refused
    write (*, '(a,i0,a)') 'errors: stat = ', stat, ', '//trim(fsym_status_message(stat))
    write (*, '(a)') '  '//trim(msg)
    ! [errors]

    ! [checks]
    call fsym_check_gradient(model, q0, worst, where, stat, msg)
    write (*, '(a,l1,a,i0,a,i0,a)') 'check_gradient: worst relative error below 1e-6: ', &
        worst < 1.0e-6_wp, ' (at dimension ', where(1), ', body ', where(2), ')'
    call fsym_check_order('A', model, q0, v0, 1.0_wp, 20, order, stat, msg)
    write (*, '(a,f4.1)') 'check_order: measured order of A on this model: ', order
    ! [checks]

contains

    !> Whether two arrays hold the same bits.
    pure logical function same_bits(a, b)
        real(wp), intent(in) :: a(:, :), b(:, :)  !! arrays of one shape
        same_bits = all(transfer(a, [0_ik]) == transfer(b, [0_ik]))
    end function same_bits

    !> A quiet NaN.
    function ieee_nan() result(x)
        use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
        real(wp) :: x
        x = ieee_value(x, ieee_quiet_nan)
    end function ieee_nan

end program fsym_example_guide
