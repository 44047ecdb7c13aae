!> The benchmark's user model: a Kepler force (mu = 1) for independent bodies in any d,
!> written as a user writes a model in the user's own module, an extension of the abstract
!> `force_model_t` (`fsym-bench ratios` runs it as `model=user`).
module fsym_bench_models
    use fsym_kinds, only: wp
    use fsym_force, only: force_model_t
    implicit none
    private

    !> Bodies attracted by a fixed centre of parameter mu, one column of q per body.
    type, extends(force_model_t), public :: user_kepler_t
        real(wp) :: mu = 1.0_wp   !! G M of the centre
    contains
        procedure :: acceleration => user_acceleration  !! -mu q_j/|q_j|^3
        procedure :: gradient => user_gradient          !! 4 mu a_j/|q_j|^3
        procedure :: has_gradient => user_has_gradient  !! true
    end type user_kepler_t

contains

    !> Accelerations of every body.
    subroutine user_acceleration(self, q, a, stat)
        class(user_kepler_t), intent(inout) :: self     !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)    !! accelerations (d, n)
        integer, intent(inout) :: stat                  !! unchanged
        real(wp) :: r2
        integer :: j
        do j = 1, size(q, 2)
            r2 = sum(q(:, j)**2)
            a(:, j) = (-self%mu / (r2 * sqrt(r2))) * q(:, j)
        end do
    end subroutine user_acceleration

    !> Gradient term of every body, given the accelerations.
    subroutine user_gradient(self, q, a, g, stat)
        class(user_kepler_t), intent(inout) :: self     !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)     !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)    !! gradient term (d, n)
        integer, intent(inout) :: stat                  !! unchanged
        real(wp) :: r2
        integer :: j
        do j = 1, size(q, 2)
            r2 = sum(q(:, j)**2)
            g(:, j) = (4.0_wp * self%mu / (r2 * sqrt(r2))) * a(:, j)
        end do
    end subroutine user_gradient

    !> The model has the gradient term.
    logical function user_has_gradient(self)
        class(user_kepler_t), intent(in) :: self        !! the model
        user_has_gradient = .true.
    end function user_has_gradient

end module fsym_bench_models
