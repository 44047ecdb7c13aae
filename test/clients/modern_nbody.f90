!> Reference for the clients: the outer solar system through the modern API
!> (`nbody_model_t`, `integrator_t`), printed in the clients' format. It uses the core modules
!> by name rather than the umbrella `fsym`, so it needs only the core library.
program modern_nbody
    use fsym_kinds, only: wp
    use fsym_nbody, only: nbody_model_t
    use fsym_integrator, only: integrator_t
    implicit none
    integer, parameter :: nb = 6
    real(wp), parameter :: mass(nb) = [0.000954786104043_wp, 0.000285583733151_wp, &
        0.0000437273164546_wp, 0.0000517759138449_wp, 7.692307692307693e-09_wp, &
        1.00000597682_wp]
    real(wp), parameter :: x0(3, nb) = reshape([ &
        -3.5023653_wp, -3.8169847_wp, -1.5507963_wp, 9.0755314_wp, -3.0458353_wp, -1.6483708_wp, &
        8.3101420_wp, -16.2901086_wp, -7.2521278_wp, 11.4707666_wp, -25.7294829_wp, &
        -10.8169456_wp, -15.5387357_wp, -25.2225594_wp, -3.1902382_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
        [3, nb])
    real(wp), parameter :: v0(3, nb) = reshape([ &
        0.00565429_wp, -0.00412490_wp, -0.00190589_wp, 0.00168318_wp, 0.00483525_wp, &
        0.00192462_wp, 0.00354178_wp, 0.00137102_wp, 0.00055029_wp, 0.00288930_wp, &
        0.00114527_wp, 0.00039677_wp, 0.00276725_wp, -0.00170702_wp, -0.00136504_wp, &
        0.0_wp, 0.0_wp, 0.0_wp], [3, nb])
    character(len=4), parameter :: names(6) = [character(len=4) :: 'FR', 'A', 'A''', 'C', &
                                                'A6', 'BM']
    type(nbody_model_t) :: model
    type(integrator_t) :: it
    real(wp) :: q(3, nb), v(3, nb)
    integer :: k, j, st
    character(len=200) :: msg
    call model%init(mass, 2.95912208286e-4_wp, stat=st, errmsg=msg)
    if (st /= 0) error stop 1
    do k = 1, size(names)
        q = x0; v = v0
        call it%init_by_name(names(k), model, 3, nb, st, msg)
        if (st /= 0) error stop 2
        do j = 1, 1000
            call it%step(model, q, v, 10.0_wp, st, msg)
            if (st /= 0) error stop 3
        end do
        do j = 1, nb
            write (*, '(a,1x,a,1x,i2,6(1x,es25.17))') 'modern', names(k), j, q(:, j), v(:, j)
        end do
        write (*, '(a,1x,a,a,2(1x,i8))') 'modern', names(k), ' counts', &
            it%force_evaluations(), it%gradient_evaluations()
    end do
end program modern_nbody
