!> Models used by several test modules.
module fsym_test_models
    use fsym, only: wp, kepler_model_t
    implicit none
    private
    public :: wrapped_kepler_t

    !> The Kepler model as a user would write it: one plain loop per body with the same
    !> arithmetic as the library's blocked force loop (`kepler_field`), so runs with either
    !> model must agree bit for bit through the one kernel.
    type, extends(kepler_model_t) :: wrapped_kepler_t
    contains
        procedure :: acceleration => plain_acceleration
        procedure :: gradient => plain_gradient
    end type wrapped_kepler_t

contains

    subroutine plain_acceleration(self, q, a, stat)
        class(wrapped_kepler_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        integer :: j
        real(wp) :: r2
        do j = 1, size(q, 2)
            r2 = sum(q(:, j)**2)
            a(:, j) = (-self%mu / (r2 * sqrt(r2))) * q(:, j)
        end do
        if (stat /= 0) return
    end subroutine plain_acceleration

    subroutine plain_gradient(self, q, a, g, stat)
        class(wrapped_kepler_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :), a(:, :)
        real(wp), intent(out), contiguous :: g(:, :)
        integer, intent(inout) :: stat
        integer :: j
        real(wp) :: r2
        do j = 1, size(q, 2)
            r2 = sum(q(:, j)**2)
            g(:, j) = (4.0_wp * self%mu / (r2 * sqrt(r2))) * a(:, j)
        end do
        if (stat /= 0) return
    end subroutine plain_gradient

end module fsym_test_models
