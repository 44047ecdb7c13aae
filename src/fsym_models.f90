!> Small standard force models with analytic gradient terms, for tests, examples and
!> stability studies: the harmonic oscillator and the Henon-Heiles potential.
module fsym_models
    use fsym_kinds, only: wp
    use fsym_force, only: force_model_t
    implicit none
    private

    !> Isotropic harmonic oscillator V = omega^2 |q|^2 / 2 for every column of q.
    type, extends(force_model_t), public :: oscillator_model_t
        real(wp) :: omega = 1.0_wp   !! angular frequency
    contains
        procedure :: acceleration => osc_acceleration   !! accelerations of every column
        procedure :: gradient => osc_gradient           !! gradient term grad |a|^2
        procedure :: has_gradient => osc_has            !! true
        procedure :: potential => osc_potential         !! potential energy summed over columns
        procedure :: has_potential => osc_has           !! true
    end type oscillator_model_t

    !> Henon-Heiles V = (x^2 + y^2)/2 + x^2 y - y^3/3 (2D, every column of q): a smooth
    !> non-central force.
    type, extends(force_model_t), public :: henon_heiles_model_t
    contains
        procedure :: acceleration => hh_acceleration    !! accelerations of every column
        procedure :: gradient => hh_gradient            !! gradient term grad |a|^2
        procedure :: has_gradient => hh_has             !! true
        procedure :: potential => hh_potential          !! potential energy summed over columns
        procedure :: has_potential => hh_has            !! true
    end type henon_heiles_model_t

contains

    !> a = -omega^2 q.
    subroutine osc_acceleration(self, q, a, stat)
        class(oscillator_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                    !! positions
        real(wp), intent(out), contiguous :: a(:, :)                   !! accelerations
        integer, intent(inout) :: stat                     !! unchanged
        associate (unused => stat); end associate   ! the interface's argument; never fails
        a = -self%omega**2 * q
    end subroutine osc_acceleration

    !> g = grad |a|^2 = 2 omega^4 q.
    subroutine osc_gradient(self, q, a, g, stat)
        class(oscillator_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                    !! positions
        real(wp), intent(in), contiguous :: a(:, :)                    !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)                   !! gradient term
        integer, intent(inout) :: stat                     !! unchanged
        associate (unused_a => a, unused => stat); end associate   ! a is not needed here
        g = 2.0_wp * self%omega**4 * q
    end subroutine osc_gradient

    !> Provided.
    logical function osc_has(self)
        class(oscillator_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate
        osc_has = .true.
    end function osc_has

    !> omega^2 |q|^2 / 2 summed.
    subroutine osc_potential(self, q, epot, stat)
        class(oscillator_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                    !! positions
        real(wp), intent(out) :: epot                      !! potential energy
        integer, intent(inout) :: stat                     !! unchanged
        associate (unused => stat); end associate
        epot = 0.5_wp * self%omega**2 * sum(q**2)
    end subroutine osc_potential

    !> a = (-x - 2xy, -y - x^2 + y^2).
    subroutine hh_acceleration(self, q, a, stat)
        class(henon_heiles_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (2, n)
        real(wp), intent(out), contiguous :: a(:, :)                     !! accelerations
        integer, intent(inout) :: stat                       !! unchanged
        integer :: j
        associate (unused_self => self, unused => stat); end associate
        do j = 1, size(q, 2)
            a(1, j) = -q(1, j) - 2.0_wp * q(1, j) * q(2, j)
            a(2, j) = -q(2, j) - q(1, j)**2 + q(2, j)**2
        end do
    end subroutine hh_acceleration

    !> g = grad |a|^2 = 2 J^T a with J the Jacobian of a.
    subroutine hh_gradient(self, q, a, g, stat)
        class(henon_heiles_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (2, n)
        real(wp), intent(in), contiguous :: a(:, :)                      !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)                     !! gradient term
        integer, intent(inout) :: stat                       !! unchanged
        integer :: j
        real(wp) :: x, y
        associate (unused_self => self, unused => stat); end associate
        do j = 1, size(q, 2)
            x = q(1, j); y = q(2, j)
            g(1, j) = 2.0_wp * (a(1, j) * (-1.0_wp - 2.0_wp * y) + a(2, j) * (-2.0_wp * x))
            g(2, j) = 2.0_wp * (a(1, j) * (-2.0_wp * x) + a(2, j) * (-1.0_wp + 2.0_wp * y))
        end do
    end subroutine hh_gradient

    !> Provided.
    logical function hh_has(self)
        class(henon_heiles_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate
        hh_has = .true.
    end function hh_has

    !> Henon-Heiles potential summed over columns.
    subroutine hh_potential(self, q, epot, stat)
        class(henon_heiles_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (2, n)
        real(wp), intent(out) :: epot                        !! potential energy
        integer, intent(inout) :: stat                       !! unchanged
        associate (unused_self => self, unused => stat); end associate
        epot = sum(0.5_wp * (q(1, :)**2 + q(2, :)**2) + q(1, :)**2 * q(2, :) - q(2, :)**3 / 3.0_wp)
    end subroutine hh_potential

end module fsym_models
