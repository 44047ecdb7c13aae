!> Integrate the paper's benchmark Kepler orbit (q = (10, 0), v = (0, 0.1), e = 0.9) for one
!> period with the forward method A and the non-forward Forest-Ruth method FR, at the same
!> number of force evaluations, and print the largest relative energy error and the final
!> position error against the exact solution.
program fsym_example_kepler
    use fsym
    implicit none
    character(len=*), parameter :: methods(2) = ['A ', 'FR']
    integer, parameter :: nforce_total = 6000   ! force evaluations per period, both methods
    type(kepler_model_t) :: model
    type(integrator_t) :: integ
    real(wp) :: q(2, 1), v(2, 1), q0(2), v0(2), qx(2), vx(2), period, h, e0, e, de_max, epot
    integer(ik) :: k, nsteps
    integer :: m, stat
    character(len=256) :: errmsg

    call kepler_paper_orbit(q0, v0, period)
    e0 = kepler_energy(q0, v0)
    write (*, '(a,f12.6,a,f10.6)') 'paper orbit: period ', period, ', energy ', e0
    write (*, '(a4,2a10,2a14)') 'name', 'steps', 'forces', 'max |dE/E0|', '|q - q_exact|'
    do m = 1, size(methods)
        call integ%init_by_name(trim(methods(m)), model, 2, 1, stat, errmsg)
        if (stat /= FSYM_SUCCESS) then
            write (*, '(a)') trim(errmsg)
            error stop 1
        end if
        ! same cost for both methods: steps = total forces / forces per step
        nsteps = nforce_total / integ%forces_per_step()
        h = period / real(nsteps, wp)
        q(:, 1) = q0
        v(:, 1) = v0
        de_max = 0.0_wp
        do k = 1, nsteps
            call integ%step(model, q, v, h, stat, errmsg)
            if (stat /= FSYM_SUCCESS) then
                write (*, '(a)') trim(errmsg)
                error stop 1
            end if
            call model%potential(q, epot, stat)
            e = 0.5_wp * sum(v**2) + epot
            de_max = max(de_max, abs((e - e0) / e0))
        end do
        call kepler_exact(q0, v0, integ%time(), qx, vx, stat)
        write (*, '(a4,2i10,2es14.4)') trim(methods(m)), integ%steps(), &
            integ%force_evaluations(), de_max, norm2(q(:, 1) - qx)
    end do
end program fsym_example_kepler
