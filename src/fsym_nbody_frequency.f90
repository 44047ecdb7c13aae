!> Local frequency of a gravitational N-body system for the integrator's step-size guard:
!> the largest omega^2 = 2 G (m_i + m_j) / s_ij^3 over the pairs (s_ij^2 = |q_i - q_j|^2 +
!> eps^2), the Kepler frequency of the pair's relative orbit at that separation. Kept apart
!> from the N-body model so that the model binds it as its `local_frequency`.
module fsym_nbody_frequency
    use fsym_kinds, only: wp
    use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
    implicit none
    private

    public :: fsym_nbody_local_frequency

contains

    !> Largest 2 G (m_i + m_j) / s_ij^3 over the pairs i < j of q(d, n), and the separation
    !> s_ij where it occurs (omega2 = 0, r = huge for a single body).
    pure subroutine fsym_nbody_local_frequency(d, n, m, g, eps, q, omega2, r)
        integer, intent(in) :: d, n                !! dimensions, bodies
        real(wp), intent(in) :: m(n)               !! masses
        real(wp), intent(in) :: g                  !! gravitational constant
        real(wp), intent(in) :: eps                !! softening length
        real(wp), intent(in) :: q(d, n)            !! positions
        real(wp), intent(out) :: omega2            !! largest pair omega^2
        real(wp), intent(out) :: r                 !! the pair's separation
        real(wp) :: s2, w2
        integer :: i, j
        omega2 = 0.0_wp; r = huge(r)
        do i = 1, n - 1
            do j = i + 1, n
                s2 = sum((q(:, i) - q(:, j))**2) + eps**2
                w2 = 2.0_wp * g * (m(i) + m(j)) / (s2 * sqrt(s2))
                if (w2 > omega2 .or. ieee_is_nan(w2)) then
                    omega2 = w2; r = sqrt(s2)
                end if
            end do
        end do
    end subroutine fsym_nbody_local_frequency

end module fsym_nbody_frequency
