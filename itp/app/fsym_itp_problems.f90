!> The benchmark problems of the imaginary-time programs (fsym_itp_bench, fsym_itp_run), in
!> one place: grid, potential, its gradient, the starting Gaussian, the coupling and the exact
!> energy where there is one.
!>   ho3d  3-D isotropic oscillator, 32^3 points, box 12, E0 = 3/2;
!>   pt1d  Poeschl-Teller V = -6 sech^2 x (lambda = 3), 256 points, box 40, E0 = -9/2;
!>   gp3d  Gross-Pitaevskii, trap frequencies (1, 1.5, 2), g = 20, 36^3 points, box 10 (no
!>         exact energy: 0 is returned).
module fsym_itp_problems
    use fsym_kinds, only: wp
    implicit none
    private
    public :: fsym_itp_problem

contains

    !> Set up problem `name` (unknown names give the oscillator).
    subroutine fsym_itp_problem(name, n, side, v, dv, psi0, g, exact)
        character(len=*), intent(in) :: name                 !! ho3d, pt1d or gp3d
        integer, allocatable, intent(out) :: n(:)            !! points per axis
        real(wp), intent(out) :: side                        !! side of the (cubic) box
        real(wp), allocatable, intent(out) :: v(:)           !! potential at the points
        real(wp), allocatable, intent(out) :: dv(:, :)       !! its gradient (npts, d)
        real(wp), allocatable, intent(out) :: psi0(:)        !! starting state
        real(wp), intent(out) :: g                           !! Gross-Pitaevskii coupling
        real(wp), intent(out) :: exact                       !! exact energy (0: none)
        real(wp) :: w(3), r(3), y
        integer :: m, i, j, k, idx
        g = 0.0_wp
        select case (name)
        case ('pt1d')
            m = 256
            n = [m]
            side = 40.0_wp
            exact = -4.5_wp
            allocate (v(m), dv(m, 1), psi0(m))
            do i = 1, m
                y = -0.5_wp * side + (i - 1) * side / m
                v(i) = -6.0_wp / cosh(y)**2
                dv(i, 1) = 12.0_wp * tanh(y) / cosh(y)**2
                psi0(i) = exp(-y**2 / 8.0_wp)
            end do
        case default
            m = 32
            side = 12.0_wp
            w = 1.0_wp
            exact = 1.5_wp
            if (name == 'gp3d') then
                m = 36
                side = 10.0_wp
                w = [1.0_wp, 1.5_wp, 2.0_wp]
                g = 20.0_wp
                exact = 0.0_wp
            end if
            n = [m, m, m]
            allocate (v(m**3), dv(m**3, 3), psi0(m**3))
            idx = 0
            do k = 1, m
                do j = 1, m
                    do i = 1, m
                        idx = idx + 1
                        r = -0.5_wp * side + ([i, j, k] - 1) * side / m
                        v(idx) = 0.5_wp * sum((w * r)**2)
                        dv(idx, :) = w**2 * r
                        psi0(idx) = exp(-sum(r**2) / 3.4_wp)
                    end do
                end do
            end do
        end select
    end subroutine fsym_itp_problem

end module fsym_itp_problems
