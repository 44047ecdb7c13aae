!> The plain force model of `fsym_example_errors`: a = -q, with no gradient term.
module fsym_plain_model
    use fsym, only: wp, force_model_t
    implicit none
    private

    !> A harmonic force without gradient term.
    type, extends(force_model_t), public :: plain_model_t
    contains
        procedure :: acceleration => plain_acceleration
    end type plain_model_t

contains

    !> a = -q.
    subroutine plain_acceleration(self, q, a, stat)
        class(plain_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions
        real(wp), intent(out), contiguous :: a(:, :)              !! accelerations
        integer, intent(inout) :: stat                !! never set
        associate (unused_self => self, unused_stat => stat); end associate   ! not needed here
        a = -q
    end subroutine plain_acceleration

end module fsym_plain_model
