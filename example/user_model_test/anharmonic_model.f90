!> A user's force model: independent particles in the anharmonic well
!> V(q) = |q|^2/2 + lambda |q|^4/4, so a = -(1 + lambda r^2) q, and the gradient term that
!> the forward methods (A, C, ...) need, g = grad |a|^2 = 2 (1 + lambda r^2)(1 + 3 lambda r^2) q.
!> With `broken = .true.` the gradient term drops the factor 3 (a plausible slip), so that
!> the test can show the checker catching it.
module anharmonic_model
    use fsym, only: wp, force_model_t
    implicit none
    private
    public :: anharmonic_model_t

    !> The anharmonic well.
    type, extends(force_model_t) :: anharmonic_model_t
        real(wp) :: lambda = 0.5_wp     !! strength of the quartic term
        logical :: broken = .false.     !! use the wrong gradient term
    contains
        procedure :: acceleration => anharmonic_acceleration  !! a = -(1 + lambda r^2) q
        procedure :: gradient => anharmonic_gradient          !! grad |a|^2
        procedure :: has_gradient => anharmonic_has_gradient  !! true
    end type anharmonic_model_t

contains

    !> Accelerations of every particle.
    subroutine anharmonic_acceleration(self, q, a, stat)
        class(anharmonic_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)       !! accelerations (d, n)
        integer, intent(inout) :: stat                     !! 0: success
        integer :: j
        do j = 1, size(q, 2)
            a(:, j) = -(1.0_wp + self%lambda * sum(q(:, j)**2)) * q(:, j)
        end do
        stat = 0
    end subroutine anharmonic_acceleration

    !> The gradient term grad |a|^2 of every particle.
    subroutine anharmonic_gradient(self, q, a, g, stat)
        class(anharmonic_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in), contiguous :: q(:, :)        !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)        !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)       !! gradient term (d, n)
        integer, intent(inout) :: stat                     !! 0: success
        real(wp) :: lr2, three
        integer :: j
        three = merge(1.0_wp, 3.0_wp, self%broken)
        do j = 1, size(q, 2)
            lr2 = self%lambda * sum(q(:, j)**2)
            g(:, j) = 2.0_wp * (1.0_wp + lr2) * (1.0_wp + three * lr2) * q(:, j)
        end do
        if (size(a) /= size(q)) stat = 1
    end subroutine anharmonic_gradient

    !> The model provides the gradient term.
    logical function anharmonic_has_gradient(self)
        class(anharmonic_model_t), intent(in) :: self      !! the model
        anharmonic_has_gradient = .true.
    end function anharmonic_has_gradient

end module anharmonic_model
