!> N-body part of `fsym-bench`: time per library step against N for a direct-summation
!> gravitational force (3D, masses, G = 1), and the share of the step spent outside the force.
!> The force model here is a minimal local one (`bench_nbody_t`), used until the library ships
!> its own N-body model.
module fsym_nbody_bench
    use, intrinsic :: iso_fortran_env, only: output_unit, int64
    use fsym
    use fsym_timing, only: median
    implicit none
    private

    !> Direct-summation gravity, pairwise (each pair once), no softening.
    type, extends(force_model_t) :: bench_nbody_t
        real(wp), allocatable :: m(:)  !! masses
    contains
        procedure :: acceleration => bench_nbody_acceleration
    end type bench_nbody_t

    public :: bench_nbody

contains

    !> a_i = sum_j m_j (q_j - q_i)/|q_j - q_i|^3.
    subroutine bench_nbody_acceleration(self, q, a, stat)
        class(bench_nbody_t), intent(inout) :: self  !! the model
        real(wp), intent(in) :: q(:, :)               !! positions (3, n)
        real(wp), intent(out) :: a(:, :)              !! accelerations (3, n)
        integer, intent(inout) :: stat                !! unchanged
        integer :: i, j, n
        real(wp) :: dx, dy, dz, r2, s, axi, ayi, azi
        n = size(q, 2)
        a = 0.0_wp
        do i = 1, n - 1
            axi = 0.0_wp; ayi = 0.0_wp; azi = 0.0_wp
            do j = i + 1, n
                dx = q(1, j) - q(1, i); dy = q(2, j) - q(2, i); dz = q(3, j) - q(3, i)
                r2 = dx * dx + dy * dy + dz * dz
                s = 1.0_wp / (r2 * sqrt(r2))
                axi = axi + self%m(j) * s * dx
                ayi = ayi + self%m(j) * s * dy
                azi = azi + self%m(j) * s * dz
                a(1, j) = a(1, j) - self%m(i) * s * dx
                a(2, j) = a(2, j) - self%m(i) * s * dy
                a(3, j) = a(3, j) - self%m(i) * s * dz
            end do
            a(1, i) = a(1, i) + axi; a(2, i) = a(2, i) + ayi; a(3, i) = a(3, i) + azi
        end do
    end subroutine bench_nbody_acceleration

    !> Print the N-body table: N, ms per FR step, us per force, share outside the force.
    subroutine bench_nbody()
        integer, parameter :: nlist(12) = [2, 4, 8, 16, 32, 64, 128, 256, 512, 1000, 2048, 4096]
        integer, parameter :: nrep = 5
        type(bench_nbody_t) :: model
        type(integrator_t) :: integ
        real(wp), allocatable :: q(:, :), v(:, :), a(:, :)
        real(wp) :: tstep(nrep), tforce(nrep), ts, tf, x(3)
        integer(int64) :: t0, t1, rate
        integer :: i, j, n, r, st, mst, nloop, k

        write (output_unit, '(a)') '## Direct-summation N-body (3D, local force model)', ''
        write (output_unit, '(a)') 'Random positions in a unit cube, random masses, small'// &
            ' velocities; library FR step (3 forces/step). outside = 1 - 3 t_force / t_step'// &
            ' (median of 5 runs each; can come out slightly negative from noise).', '', &
            '| N | us per step | us per force | outside the force |', '|---|---|---|---|'
        do i = 1, size(nlist)
            n = nlist(i)
            allocate (q(3, n), v(3, n), a(3, n))
            if (allocated(model%m)) deallocate (model%m)
            allocate (model%m(n))
            do j = 1, n
                call random_number(x)
                q(:, j) = x
                call random_number(x)
                v(:, j) = 0.01_wp * (x - 0.5_wp)
                model%m(j) = 1.0_wp / real(n, wp) * (0.5_wp + x(1))
            end do
            call integ%init_by_name('FR', model, 3, n, st)
            nloop = max(1, int(2.0e7_wp / (real(n, wp)**2)))
            do r = 1, nrep
                call system_clock(t0, rate)
                do k = 1, nloop
                    mst = 0
                    call model%acceleration(q, a, mst)
                end do
                call system_clock(t1)
                tforce(r) = real(t1 - t0, wp) / real(rate, wp) / real(nloop, wp)
                call system_clock(t0)
                do k = 1, max(1, nloop / 3)
                    call integ%step(model, q, v, 1.0e-6_wp)
                end do
                call system_clock(t1)
                tstep(r) = real(t1 - t0, wp) / real(rate, wp) / real(max(1, nloop / 3), wp)
            end do
            ts = median(tstep); tf = median(tforce)
            write (output_unit, '(a,i0,a,f0.3,a,f0.3,a,f0.2,a)') '| ', n, ' | ', ts * 1.0e6_wp, &
                ' | ', tf * 1.0e6_wp, ' | ', 100.0_wp * (1.0_wp - 3.0_wp * tf / ts), ' % |'
            deallocate (q, v, a)
        end do
        write (output_unit, '(a)') ''
    end subroutine bench_nbody

end module fsym_nbody_bench
