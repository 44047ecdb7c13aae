!> N-body part of `fsym-bench`: time per library step against N for the library's
!> direct-summation gravitational model (`nbody_model_t`, 3D, masses, G = 1), and the share of
!> the step spent outside the force.
module fsym_nbody_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_nbody, only: nbody_model_t
    use fsym_timing, only: median, seconds_since
    implicit none
    private

    !> A force model that costs nothing (a = 0): a step with it is the step without the force.
    type, extends(force_model_t) :: zero_model_t
    contains
        procedure :: acceleration => zero_acceleration
    end type zero_model_t

    public :: bench_nbody

contains

    !> a = 0.
    subroutine zero_acceleration(self, q, a, stat)
        class(zero_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)              !! positions
        real(wp), intent(out), contiguous :: a(:, :)             !! accelerations (zero)
        integer, intent(inout) :: stat               !! unchanged
        associate (unused_q => q, unused_self => self, unused_stat => stat); end associate
        a = 0.0_wp
    end subroutine zero_acceleration

    !> Print the N-body table: N, us per FR step, us per force, share outside the force.
    subroutine bench_nbody()
        integer, parameter :: nlist(12) = [2, 4, 8, 16, 32, 64, 128, 256, 512, 1000, 2048, 4096]
        integer, parameter :: nrep = 5
        type(nbody_model_t) :: model
        type(zero_model_t) :: zero
        type(integrator_t) :: integ, integ0
        real(wp), allocatable :: q(:, :), v(:, :), a(:, :), m(:)
        real(wp) :: tstep(nrep), tforce(nrep), tzero(nrep), ts, tf, tz, x(3)
        integer(int64) :: t0
        integer :: i, j, n, r, st, mst, nloop, nstep, k

        write (output_unit, '(a)') '## Direct-summation N-body (3D, `nbody_model_t`)', ''
        write (output_unit, '(a)') 'Random positions in a unit cube, masses (0.5..1.5)/N, small'// &
            ' velocities; library FR step (3 forces/step, h = 1e-6) through `integrator_t%step`'// &
            ' (the one kernel, the model called through its type-bound procedure).'// &
            ' Force = `model%acceleration` alone. Outside (difference) ='// &
            ' 1 - 3 t_force / t_step (noise can make it negative); outside (direct) ='// &
            ' t_zero / t_step with t_zero the same step with a force model that costs nothing'// &
            ' (a = 0). Medians of 5 runs each.', '', &
            '| N | us per step | us per force | us per step, zero force | '// &
            'outside (difference) | outside (direct) |', '|---|---|---|---|---|---|'
        do i = 1, size(nlist)
            n = nlist(i)
            allocate (q(3, n), v(3, n), a(3, n), m(n))
            do j = 1, n
                call random_number(x)
                q(:, j) = x
                call random_number(x)
                v(:, j) = 0.01_wp * (x - 0.5_wp)
                m(j) = (0.5_wp + x(1)) / real(n, wp)
            end do
            call model%init(m, 1.0_wp)
            call integ%init_by_name('FR', model, 3, n, st)
            call integ0%init_by_name('FR', zero, 3, n, st)
            nloop = max(1, int(3.0e7_wp / (real(n, wp)**2)))
            nstep = max(1, nloop / 3)
            do r = 1, nrep
                call system_clock(t0)
                do k = 1, nloop
                    mst = 0
                    call model%acceleration(q, a, mst)
                end do
                tforce(r) = seconds_since(t0) / real(nloop, wp)
                call system_clock(t0)
                do k = 1, nstep
                    call integ%step(model, q, v, 1.0e-6_wp)
                end do
                tstep(r) = seconds_since(t0) / real(nstep, wp)
                call system_clock(t0)
                do k = 1, max(nstep, 1000)
                    call integ0%step(zero, q, v, 1.0e-6_wp)
                end do
                tzero(r) = seconds_since(t0) / real(max(nstep, 1000), wp)
            end do
            ts = median(tstep); tf = median(tforce); tz = median(tzero)
            write (output_unit, '(a,i0,3(a,f12.3),2(a,f8.3),a)') '| ', n, ' | ', ts * 1.0e6_wp, &
                ' | ', tf * 1.0e6_wp, ' | ', tz * 1.0e6_wp, ' | ', &
                100.0_wp * (1.0_wp - 3.0_wp * tf / ts), ' % | ', 100.0_wp * tz / ts, ' % |'
            deallocate (q, v, a, m)
        end do
        write (output_unit, '(a)') ''
    end subroutine bench_nbody

end module fsym_nbody_bench
