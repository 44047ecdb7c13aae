!> The error fingerprints of a planar Kepler run used by the study programs (no I/O): the
!> energy error coefficient (E(t) - E0)/(E0 eps^4), the precession error coefficient (signed
!> rotation angle of the Laplace-Runge-Lenz vector from its start, counter-clockwise positive,
!> divided by eps^4), their maxima over a run, and the eps vs eps/2 convergence check that
!> S. A. Chin, *Forward and non-forward symplectic integrators in solving classical dynamics
!> problems*, Int. J. Comput. Math. 84(6), 729-747 (2007), doi:10.1080/00207160701458476,
!> requires before it calls a curve a fingerprint.
!>
!> The rotation is measured against the start vector A0 itself, as atan2(A0 x A, A0 . A):
!> a small rotation comes out to full relative precision whatever the direction of A0 (the
!> paper's orbit has A0 on atan2's branch cut at +-pi, where differences of absolute
!> directions lose everything below ulp(2 pi)). Turns beyond +-pi are unwrapped by whole
!> multiples of 2 pi, which leave the small-angle value untouched.
module fsym_diagnostics
    use fsym_kinds, only: wp
    use fsym_kepler, only: kepler_energy, kepler_lrl, FSYM_PI
    implicit none
    private

    public :: fsym_energy_coefficient, fsym_angle_step, fsym_unwrap_angles
    public :: fsym_relative_difference, fsym_vector_angle

    !> Running error coefficients of one planar Kepler run: `init` at the start state, then
    !> `update` after every step. Holds no arrays, so it never allocates.
    type, public :: coefficient_tracker_t
        real(wp) :: eps = 0.0_wp          !! time step (the coefficients divide by eps^4)
        real(wp) :: mu = 1.0_wp           !! G M
        real(wp) :: e0 = 0.0_wp           !! energy at the start
        real(wp) :: lrl0(2) = 0.0_wp      !! LRL vector at the start
        real(wp) :: rotation = 0.0_wp     !! unwrapped rotation of the LRL vector since start
        real(wp) :: energy = 0.0_wp       !! current energy coefficient
        real(wp) :: precession = 0.0_wp   !! current precession coefficient
        real(wp) :: energy_max = 0.0_wp   !! max |energy coefficient| so far
        real(wp) :: precession_max = 0.0_wp  !! max |precession coefficient| so far
    contains
        procedure :: init => tracker_init
        procedure :: update => tracker_update
    end type coefficient_tracker_t

contains

    !> Energy error coefficient (e - e0)/(e0 eps^4).
    pure elemental real(wp) function fsym_energy_coefficient(e, e0, eps)
        real(wp), intent(in) :: e     !! energy now
        real(wp), intent(in) :: e0    !! energy at the start
        real(wp), intent(in) :: eps   !! time step
        fsym_energy_coefficient = (e - e0) / (e0 * eps**4)
    end function fsym_energy_coefficient

    !> The signed change from angle `a` to angle `b` (both in [-pi, pi], e.g. from atan2),
    !> wrapped to (-pi, pi]: the rotation between two directions that are sampled closely
    !> enough. A change already in (-pi, pi] is returned as the plain difference b - a
    !> (no modulo, so no rounding to multiples of ulp(2 pi)).
    pure elemental real(wp) function fsym_angle_step(a, b)
        real(wp), intent(in) :: a  !! earlier direction (radians)
        real(wp), intent(in) :: b  !! later direction (radians)
        real(wp) :: d
        d = b - a
        if (d > FSYM_PI) then
            d = d - 2.0_wp * FSYM_PI
        else if (d <= -FSYM_PI) then
            d = d + 2.0_wp * FSYM_PI
        end if
        fsym_angle_step = d
    end function fsym_angle_step

    !> Signed angle from vector `a` to vector `b` (2D), atan2(a x b, a . b), in (-pi, pi]:
    !> full relative precision for small angles whatever the directions.
    pure real(wp) function fsym_vector_angle(a, b)
        real(wp), intent(in) :: a(2)  !! from this vector
        real(wp), intent(in) :: b(2)  !! to this vector
        fsym_vector_angle = atan2(a(1) * b(2) - a(2) * b(1), a(1) * b(1) + a(2) * b(2))
    end function fsym_vector_angle

    !> Unwrap a sequence of directions: out(1) = theta(1), each later value differs from the
    !> previous one by the wrapped step, so the total is the accumulated signed rotation.
    pure subroutine fsym_unwrap_angles(theta, out)
        real(wp), intent(in) :: theta(:)   !! directions (radians, e.g. from atan2)
        real(wp), intent(out) :: out(:)    !! unwrapped directions, same size
        integer :: k
        if (size(theta) == 0) return
        out(1) = theta(1)
        do k = 2, size(theta)
            out(k) = out(k - 1) + fsym_angle_step(theta(k - 1), theta(k))
        end do
    end subroutine fsym_unwrap_angles

    !> Relative difference |a - b| / max(|a|, |b|) (0 when both are 0): the eps vs eps/2
    !> convergence check of a coefficient.
    pure elemental real(wp) function fsym_relative_difference(a, b)
        real(wp), intent(in) :: a, b  !! the coefficient at eps and at eps/2
        real(wp) :: s
        s = max(abs(a), abs(b))
        if (s <= 0.0_wp) then   ! s >= 0: s == 0
            fsym_relative_difference = 0.0_wp
        else
            fsym_relative_difference = abs(a - b) / s
        end if
    end function fsym_relative_difference

    !> Start tracking at the state (q, v) with time step eps.
    pure subroutine tracker_init(self, q, v, eps, mu)
        class(coefficient_tracker_t), intent(inout) :: self  !! the tracker
        real(wp), intent(in) :: q(2), v(2)                   !! start state
        real(wp), intent(in) :: eps                          !! time step
        real(wp), intent(in), optional :: mu                 !! G M (default 1)
        self%mu = 1.0_wp
        if (present(mu)) self%mu = mu
        self%eps = eps
        self%e0 = kepler_energy(q, v, self%mu)
        call kepler_lrl(q, v, self%lrl0, self%mu)
        self%rotation = 0.0_wp
        self%energy = 0.0_wp
        self%precession = 0.0_wp
        self%energy_max = 0.0_wp
        self%precession_max = 0.0_wp
    end subroutine tracker_init

    !> Take the state after a step: update the coefficients and their maxima. The LRL
    !> vector must turn by less than pi between updates (it turns by O(eps^4) per step).
    pure subroutine tracker_update(self, q, v)
        class(coefficient_tracker_t), intent(inout) :: self  !! the tracker
        real(wp), intent(in) :: q(2), v(2)                   !! state now
        real(wp) :: lrl(2), rel, turns
        call kepler_lrl(q, v, lrl, self%mu)
        rel = fsym_vector_angle(self%lrl0, lrl)      ! in (-pi, pi], exact near 0
        turns = anint((self%rotation - rel) / (2.0_wp * FSYM_PI))
        if (abs(turns) < 0.5_wp) then   ! turns is a whole number: turns == 0
            self%rotation = rel
        else
            self%rotation = rel + turns * (2.0_wp * FSYM_PI)
        end if
        self%energy = fsym_energy_coefficient(kepler_energy(q, v, self%mu), self%e0, self%eps)
        self%precession = self%rotation / self%eps**4
        self%energy_max = max(self%energy_max, abs(self%energy))
        self%precession_max = max(self%precession_max, abs(self%precession))
    end subroutine tracker_update

end module fsym_diagnostics
