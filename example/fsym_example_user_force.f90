!> A user force model: a chain of point masses in 3D joined by springs, with the masses and
!> the spring constants kept in the extension of `force_model_t`. The model reports a failure
!> through `stat` when two neighbours coincide (the spring direction is then undefined).
!> The chain is integrated with FR and with A' (A with the gradient term by extrapolation,
!> since this model provides no gradient), and the energy drift is printed. Last, a step from
!> a configuration the model refuses shows its failure coming back as a status.
program fsym_example_user_force
    use fsym
    use fsym_chain_model, only: chain_model_t
    implicit none
    integer, parameter :: n = 4
    character(len=*), parameter :: methods(2) = ['FR', 'A ']
    type(chain_model_t) :: chain
    type(integrator_t) :: integ
    real(wp) :: q(3, n), v(3, n), q_before(3, n), e0, e1, h
    integer :: j, m, stat
    character(len=256) :: errmsg

    chain%m = [1.0_wp, 2.0_wp, 2.0_wp, 1.0_wp]
    chain%k = [10.0_wp, 5.0_wp, 10.0_wp]
    h = 0.01_wp

    do m = 1, size(methods)
        ! a stretched, twisted chain at rest in the centre-of-mass frame
        do j = 1, n
            q(:, j) = [1.2_wp * (j - 1), 0.1_wp * sin(real(j, wp)), 0.0_wp]
            v(:, j) = [0.0_wp, 0.0_wp, 0.3_wp * (-1)**j] / chain%m(j)
        end do
        ! A needs the gradient term; this model has none, so ask for A' (extrapolate)
        call integ%init_by_name(trim(methods(m)), chain, 3, n, stat, errmsg, extrapolate=.true.)
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a)') 'init failed: '//trim(errmsg)
            error stop 1
        end if
        e0 = energy(chain, q, v)
        call integ%run(chain, q, v, h, 10000_ik, stat, errmsg)
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a,i0,a)') 'run stopped after ', integ%steps(), ' steps: '//trim(errmsg)
            error stop 1
        end if
        e1 = energy(chain, q, v)
        write (*, '(a,a4,a,f8.2,a,i0,a,es10.3)') 'method ', integ%name(), ' t = ', &
            integ%time(), ', forces ', integ%force_evaluations(), ', relative energy error ', &
            abs((e1 - e0) / e0)
    end do
    write (*, '(a,i0)') 'force evaluations seen by the model: ', chain%calls

    ! the model's own failure: put mass 2 on top of mass 1; the step is refused and undone
    q(:, 2) = q(:, 1)
    q_before = q
    call integ%step(chain, q, v, h, stat, errmsg)
    write (*, '(a,i0,a,l1)') 'coincident masses: stat = ', stat, ', q unchanged: ', &
        all(q <= q_before .and. q >= q_before)   ! q == q_before, element by element
    write (*, '(a)') '  '//trim(errmsg)

contains

    !> Kinetic plus potential energy.
    function energy(model, q, v) result(e)
        type(chain_model_t), intent(inout) :: model  !! the chain
        real(wp), intent(in) :: q(:, :), v(:, :)    !! state
        real(wp) :: e
        integer :: st
        st = 0
        call model%potential(q, e, st)
        e = e + 0.5_wp * sum(spread(model%m, 1, size(v, 1)) * v**2)
    end function energy

end program fsym_example_user_force
