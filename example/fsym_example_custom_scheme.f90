!> A scheme from the user's own coefficient arrays: the fourth-order triple jump (Forest-Ruth)
!> written in velocity form, kick first. Its metadata are derived from the table, its order
!> is measured on the harmonic oscillator, and an inconsistent table is rejected with a status
!> and a message, leaving the scheme variable as it was.
program fsym_example_custom_scheme
    use fsym
    implicit none
    type(scheme_t) :: scheme
    type(oscillator_model_t) :: model
    type(integrator_t) :: integ
    real(wp) :: x1, x0, hs(4), errs(4), q(1, 1), v(1, 1), t_end
    integer :: stat, i
    integer(ik) :: nsteps
    character(len=256) :: errmsg

    x1 = 1.0_wp / (2.0_wp - 2.0_wp**(1.0_wp / 3.0_wp))
    x0 = 1.0_wp - 2.0_wp * x1
    ! kick x1/2, drift x1, kick (x1+x0)/2, drift x0, kick (x0+x1)/2, drift x1, kick x1/2
    call fsym_scheme_custom('triple-jump', &
        [OP_KICK, OP_DRIFT, OP_KICK, OP_DRIFT, OP_KICK, OP_DRIFT, OP_KICK], &
        [0.5_wp * x1, x1, 0.5_wp * (x1 + x0), x0, 0.5_wp * (x0 + x1), x1, 0.5_wp * x1], &
        [(0.0_wp, i = 1, 7)], 4, scheme, stat, errmsg)
    if (stat /= FSYM_SUCCESS) then
        write (*, '(a)') trim(errmsg)
        error stop 1
    end if
    write (*, '(a)') 'scheme '//scheme%name//':'
    write (*, '(a)', advance='no') scheme%describe()
    write (*, '(a,l2,a,l2,a,l2,a,i0,a,i0)') 'forward', scheme%forward, ', symplectic', &
        scheme%symplectic, ', symmetric', scheme%symmetric, ', forces per step ', &
        scheme%nforce, ', gradients per step ', scheme%ngrad

    ! measured order: error at t = 10 of x'' = -x, x(0) = 1, v(0) = 0, for halving steps
    t_end = 10.0_wp
    do i = 1, size(hs)
        nsteps = 50_ik * 2_ik**(i - 1)
        hs(i) = t_end / real(nsteps, wp)
        call integ%init(scheme, model, 1, 1, stat, errmsg)
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a)') trim(errmsg)
            error stop 1
        end if
        q = 1.0_wp
        v = 0.0_wp
        call integ%run(model, q, v, hs(i), nsteps, stat, errmsg)
        errs(i) = hypot(q(1, 1) - cos(t_end), v(1, 1) + sin(t_end))
        write (*, '(a,f8.5,a,es10.3)') 'h = ', hs(i), '  error = ', errs(i)
    end do
    write (*, '(a,f6.3)') 'fitted order: ', fsym_order_fit(hs, errs)

    ! an inconsistent table: the drifts sum to 0.9, not 1
    call fsym_scheme_custom('broken', [OP_KICK, OP_DRIFT, OP_KICK], &
                            [0.5_wp, 0.9_wp, 0.5_wp], [0.0_wp, 0.0_wp, 0.0_wp], 2, scheme, &
                            stat, errmsg)
    write (*, '(a,i0)') 'broken table: stat = ', stat
    write (*, '(a)') '  message: '//trim(errmsg)
    write (*, '(a)') '  scheme still holds: '//scheme%name
end program fsym_example_custom_scheme
