!> Record where the force is evaluated: two steps of A' (A with the extrapolated gradient
!> force) and of FR on the paper's Kepler orbit, with a `trace_recorder_t` attached to `step`.
!> Each line is one evaluation: step, stage, kind (force, gradient, extrapolated) and position.
program fsym_example_trace
    use fsym
    implicit none
    character(len=*), parameter :: methods(2) = ['A''', 'FR']
    character(len=*), parameter :: kinds(3) = ['force       ', 'gradient    ', 'extrapolated']
    type(kepler_model_t) :: model
    type(integrator_t) :: integ
    type(trace_recorder_t) :: trace
    real(wp) :: q(2, 1), v(2, 1), period
    integer :: i, m, stat
    integer(ik) :: k
    character(len=256) :: errmsg

    do m = 1, size(methods)
        call kepler_paper_orbit(q(:, 1), v(:, 1), period)
        call integ%init_by_name(trim(methods(m)), model, 2, 1, stat, errmsg)
        if (stat == FSYM_SUCCESS) call trace%init(2, 1, 8, stat, errmsg)  ! room for 8 points
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a)') trim(errmsg)
            error stop 1
        end if
        do k = 1, 2
            call integ%step(model, q, v, period / 100.0_wp, stat, errmsg, recorder=trace)
            if (stat /= FSYM_SUCCESS) then
                write (*, '(a)') trim(errmsg)
                error stop 1
            end if
        end do
        write (*, '(a,i0,a,i0,a)') 'method '//integ%name()//': ', trace%count, &
            ' points recorded, ', trace%dropped, ' dropped'
        write (*, '(a6,a7,a14,2a14)') 'step', 'stage', 'kind', 'x', 'y'
        do i = 1, trace%count
            write (*, '(i6,i7,a14,2f14.8)') trace%step(i), trace%stage(i), &
                trim(kinds(trace%kind(i))), trace%q(:, 1, i)
        end do
    end do
end program fsym_example_trace
