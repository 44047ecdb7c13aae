!> Bad input returns a status code and a message, never stops the program when `stat` is
!> passed, and leaves the caller's state exactly as it was: an unknown method, a zero step, a
!> NaN in the state, mismatched shapes, a force that becomes infinite in the middle of a step,
!> and a method that needs a gradient the model lacks.
program fsym_example_errors
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use fsym
    use fsym_plain_model, only: plain_model_t
    implicit none
    type(kepler_model_t) :: kepler
    type(plain_model_t) :: plain
    type(integrator_t) :: integ
    type(scheme_t) :: fr
    real(wp) :: q(2, 1), v(2, 1), q_in(2, 1), v_in(2, 1), qbad(3, 1), vbad(3, 1), c1
    integer :: stat
    character(len=256) :: errmsg

    ! 1. unknown method name
    call integ%init_by_name('B7', kepler, 2, 1, stat, errmsg)
    call show('unknown method')

    call integ%init_by_name('FR', kepler, 2, 1, stat, errmsg)
    call show('FR set up')
    q(:, 1) = [1.0_wp, 0.0_wp]
    v(:, 1) = [0.0_wp, 1.0_wp]

    ! 2. zero step
    q_in = q; v_in = v
    call integ%step(kepler, q, v, 0.0_wp, stat, errmsg)
    call show('zero step', same(q, q_in) .and. same(v, v_in))

    ! 3. NaN in the state
    v(2, 1) = ieee_value(1.0_wp, ieee_quiet_nan)
    q_in = q; v_in = v
    call integ%step(kepler, q, v, 0.1_wp, stat, errmsg)
    call show('NaN velocity', same(q, q_in) .and. same(v, v_in))
    v(:, 1) = [0.0_wp, 1.0_wp]

    ! 4. arrays of another shape than given to init
    qbad = 1.0_wp
    vbad = 0.5_wp
    call integ%step(kepler, qbad, vbad, 0.1_wp, stat, errmsg)
    call show('wrong shape', all(qbad <= 1.0_wp .and. qbad >= 1.0_wp) .and. &
        all(vbad <= 0.5_wp .and. vbad >= 0.5_wp))   ! still all 1 and all 0.5

    ! 5. a step whose first drift lands exactly on the singularity q = 0: the force there is
    !    not finite, so the step is undone
    fr = integ%scheme()
    c1 = fr%c(1)                       ! FR starts with a drift of weight c1
    q(:, 1) = [c1, 0.0_wp]
    v(:, 1) = [-1.0_wp, 0.0_wp]
    q_in = q; v_in = v
    call integ%step(kepler, q, v, 1.0_wp, stat, errmsg)
    call show('through q = 0', same(q, q_in) .and. same(v, v_in))

    ! 6. the scheme needs a gradient term the model does not provide
    call integ%init_by_name('A', plain, 2, 1, stat, errmsg)
    call show('A without gradient')
    call integ%init_by_name('A', plain, 2, 1, stat, errmsg, extrapolate=.true.)
    call show('A with extrapolate')
    write (*, '(a)') 'the integrator is now '//integ%name()

contains

    !> Print the status and message, and for a step whether the state is unchanged.
    subroutine show(what, unchanged)
        character(len=*), intent(in) :: what          !! the case
        logical, intent(in), optional :: unchanged    !! the state equals its saved copy
        if (stat == FSYM_SUCCESS) then
            write (*, '(a22,a)') what//': ', 'ok'
        else if (present(unchanged)) then
            write (*, '(a22,a,i0,a,l1)') what//': ', 'stat = ', stat, ', state unchanged: ', &
                unchanged
        else
            write (*, '(a22,a,i0)') what//': ', 'stat = ', stat
        end if
        if (stat /= FSYM_SUCCESS) write (*, '(a22,a)') '', trim(errmsg)
    end subroutine show

    !> Equal element by element, a NaN counting as equal to a NaN (a == b written as
    !> a <= b .and. a >= b: the same test, without gfortran's -Wcompare-reals note).
    pure logical function same(a, b)
        real(wp), intent(in) :: a(:, :), b(:, :)  !! arrays of one shape
        same = all((a <= b .and. a >= b) .or. (ieee_is_nan(a) .and. ieee_is_nan(b)))
    end function same

end program fsym_example_errors
