!> The fpm consumer: a Kepler orbit with method A through `use fsym`, and the failure path
!> (an unknown label returns a status). Prints the energy error after one period; exits
!> non-zero if anything fails.
program fsym_fpm_consumer
    use fsym
    implicit none
    type(kepler_model_t) :: kep
    type(integrator_t) :: it
    real(wp) :: q(2, 1), v(2, 1), e0, e1
    integer :: st
    character(len=200) :: msg

    q(:, 1) = [1.0_wp, 0.0_wp]
    v(:, 1) = [0.0_wp, 1.0_wp]
    call it%init_by_name('A', kep, 2, 1, st, msg)
    if (st /= FSYM_SUCCESS) error stop 'init failed'
    e0 = kepler_energy(q(:, 1), v(:, 1))
    call it%run(kep, q, v, 2.0_wp * FSYM_PI / 1000.0_wp, 1000_ik, stat=st, errmsg=msg)
    if (st /= FSYM_SUCCESS) error stop 'run failed'
    e1 = kepler_energy(q(:, 1), v(:, 1))
    write (*, '(a,es10.3)') 'A, one circular period at h = P/1000: |dE/E| = ', abs((e1 - e0) / e0)
    call it%init_by_name('A46342', kep, 2, 1, st, msg)
    if (st == FSYM_SUCCESS) error stop 'A46342 accepted'
    write (*, '(a,i0,2a)') 'A46342: status ', st, ', ', trim(msg)
end program fsym_fpm_consumer
