!> The user force model of `fsym_example_user_force`: a chain of point masses in 3D joined
!> by springs, with masses and spring constants kept in the extension of `force_model_t`.
module fsym_chain_model
    use fsym, only: wp, force_model_t
    implicit none
    private

    !> n masses m(j) in a line; spring j joins masses j and j+1 with stiffness k(j) and rest
    !> length len0.
    type, extends(force_model_t), public :: chain_model_t
        real(wp), allocatable :: m(:)   !! masses (n)
        real(wp), allocatable :: k(:)   !! spring constants (n-1)
        real(wp) :: len0 = 1.0_wp       !! rest length of every spring
        integer :: calls = 0            !! force evaluations seen by the model
    contains
        procedure :: acceleration => chain_acceleration
        procedure :: potential => chain_potential
        procedure :: has_potential => chain_has_potential
    end type chain_model_t

contains

    !> a_j = (1/m_j) sum of the spring forces on mass j; stat = 1 if two neighbours coincide.
    subroutine chain_acceleration(self, q, a, stat)
        class(chain_model_t), intent(inout) :: self  !! the chain
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (3, n)
        real(wp), intent(out), contiguous :: a(:, :)              !! accelerations (3, n)
        integer, intent(inout) :: stat                !! set to 1 on failure
        real(wp) :: dq(size(q, 1)), r, f(size(q, 1))
        integer :: j
        self%calls = self%calls + 1
        a = 0.0_wp
        do j = 1, size(q, 2) - 1
            dq = q(:, j + 1) - q(:, j)
            r = norm2(dq)
            if (r <= 0.0_wp) then   ! coincident masses (r >= 0)
                stat = 1
                return
            end if
            f = self%k(j) * (r - self%len0) * dq / r     ! pull on mass j towards j+1
            a(:, j) = a(:, j) + f / self%m(j)
            a(:, j + 1) = a(:, j + 1) - f / self%m(j + 1)
        end do
    end subroutine chain_acceleration

    !> Sum of k_j (r_j - len0)^2 / 2.
    subroutine chain_potential(self, q, epot, stat)
        class(chain_model_t), intent(inout) :: self  !! the chain
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (3, n)
        real(wp), intent(out) :: epot                 !! potential energy
        integer, intent(inout) :: stat                !! never set
        integer :: j
        associate (unused_stat => stat); end associate   ! not needed here
        epot = 0.0_wp
        do j = 1, size(q, 2) - 1
            epot = epot + 0.5_wp * self%k(j) * (norm2(q(:, j + 1) - q(:, j)) - self%len0)**2
        end do
    end subroutine chain_potential

    !> The chain provides its potential.
    logical function chain_has_potential(self)
        class(chain_model_t), intent(in) :: self  !! the chain
        associate (unused_self => self); end associate   ! not needed here
        chain_has_potential = .true.
    end function chain_has_potential

end module fsym_chain_model
