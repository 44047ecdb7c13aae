!> The model and the observer of the user guide (`doc/pages/guide.md`, program
!> `fsym_example_guide`): independent bodies in 3-D, each around a softened central mass
!> (a Plummer sphere, V(r) = -mu / s with s^2 = r^2 + eps^2), with everything a model can
!> give: accelerations, the gradient term, the potential and the local frequency for the
!> step-size guard. The observer records the largest energy error it sees.
module fsym_guide_model
    use fsym, only: wp, ik, force_model_t, observer_t
    implicit none
    private

    ! [model]
    !> Bodies around a softened central mass: a = -mu q / s^3, s^2 = |q|^2 + eps^2.
    type, extends(force_model_t), public :: plummer_model_t
        real(wp) :: mu = 1.0_wp        !! G times the central mass
        real(wp) :: eps = 0.1_wp       !! softening length (> 0)
    contains
        procedure :: acceleration => plummer_acceleration      ! required
        procedure :: gradient => plummer_gradient              ! optional: for A, C, AN, ...
        procedure :: has_gradient => plummer_has
        procedure :: potential => plummer_potential            ! optional: energies
        procedure :: has_potential => plummer_has
        procedure :: local_frequency => plummer_frequency      ! optional: the guard
        procedure :: has_frequency => plummer_has
    end type plummer_model_t
    ! [model]

    ! [observer]
    !> Tracks the worst relative energy error |E/E0 - 1| seen at the observed steps.
    type, extends(observer_t), public :: energy_watch_t
        type(plummer_model_t) :: model   !! a copy of the model, for the energy
        real(wp) :: e0 = 0.0_wp          !! energy at the start
        real(wp) :: worst = 0.0_wp       !! worst relative error seen
        integer :: calls = 0             !! times called
    contains
        procedure :: observe => watch_observe
    end type energy_watch_t
    ! [observer]

    public :: plummer_energy

contains

    ! [acceleration]
    !> a_j = -mu q_j / s_j^3. The model refuses coincident bodies with nothing: a Plummer
    !> sphere has no singularity, so stat stays 0.
    subroutine plummer_acceleration(self, q, a, stat)
        class(plummer_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (3, n)
        real(wp), intent(out), contiguous :: a(:, :)   !! accelerations (3, n)
        integer, intent(inout) :: stat                 !! 0 on entry; set non-zero to fail
        real(wp) :: s2
        integer :: j
        if (.not. (self%eps > 0.0_wp)) then
            stat = 1   ! the step is undone and the caller gets FSYM_ERR_MODEL
            return
        end if
        do j = 1, size(q, 2)
            s2 = sum(q(:, j)**2) + self%eps**2
            a(:, j) = -self%mu * q(:, j) / (s2 * sqrt(s2))
        end do
    end subroutine plummer_acceleration
    ! [acceleration]

    ! [gradient]
    !> g_j = grad |a_j|^2 = 2 mu^2 q_j (s^2 - 3 r^2) / s^8 (unit masses).
    subroutine plummer_gradient(self, q, a, g, stat)
        class(plummer_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (3, n)
        real(wp), intent(in), contiguous :: a(:, :)    !! accelerations at q (not needed here)
        real(wp), intent(out), contiguous :: g(:, :)   !! gradient term (3, n)
        integer, intent(inout) :: stat                 !! 0 on entry; set non-zero to fail
        real(wp) :: r2, s2
        integer :: j
        associate (unused_a => a, unused_stat => stat); end associate
        do j = 1, size(q, 2)
            r2 = sum(q(:, j)**2)
            s2 = r2 + self%eps**2
            g(:, j) = 2.0_wp * self%mu**2 * q(:, j) * (s2 - 3.0_wp * r2) / s2**4
        end do
    end subroutine plummer_gradient
    ! [gradient]

    !> Provided (gradient, potential and local frequency alike).
    logical function plummer_has(self)
        class(plummer_model_t), intent(in) :: self  !! the model
        associate (unused => self); end associate
        plummer_has = .true.
    end function plummer_has

    !> V = -mu sum_j 1 / s_j.
    subroutine plummer_potential(self, q, epot, stat)
        class(plummer_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (3, n)
        real(wp), intent(out) :: epot                  !! potential energy
        integer, intent(inout) :: stat                 !! 0 on entry
        integer :: j
        associate (unused => stat); end associate
        epot = 0.0_wp
        do j = 1, size(q, 2)
            epot = epot - self%mu / sqrt(sum(q(:, j)**2) + self%eps**2)
        end do
    end subroutine plummer_potential

    ! [frequency]
    !> Largest omega^2 = 2 mu / s^3 over the bodies (the Kepler value with r -> s), and the
    !> distance where it occurs: the guard refuses a step with |h| omega above the method's
    !> stability limit.
    subroutine plummer_frequency(self, q, omega2, r, stat)
        class(plummer_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)    !! positions (3, n)
        real(wp), intent(out) :: omega2                !! largest local omega^2
        real(wp), intent(out) :: r                     !! distance where it occurs
        integer, intent(inout) :: stat                 !! 0 on entry
        real(wp) :: s2, w2
        integer :: j
        associate (unused => stat); end associate
        omega2 = 0.0_wp; r = 0.0_wp
        do j = 1, size(q, 2)
            s2 = sum(q(:, j)**2) + self%eps**2
            w2 = 2.0_wp * self%mu / (s2 * sqrt(s2))
            if (w2 > omega2) then
                omega2 = w2; r = sqrt(sum(q(:, j)**2))
            end if
        end do
    end subroutine plummer_frequency
    ! [frequency]

    !> Total energy (unit masses): kinetic plus potential.
    function plummer_energy(model, q, v) result(e)
        type(plummer_model_t), intent(in) :: model  !! the model
        real(wp), intent(in) :: q(:, :)             !! positions (3, n)
        real(wp), intent(in) :: v(:, :)             !! velocities (3, n)
        real(wp) :: e
        integer :: j
        e = 0.5_wp * sum(v**2)
        do j = 1, size(q, 2)
            e = e - model%mu / sqrt(sum(q(:, j)**2) + model%eps**2)
        end do
    end function plummer_energy

    ! [observe]
    !> Called every `every` steps by run/run_to: the energy error so far; stops the run if
    !> it ever exceeds 1e-3 (a run stopped by its observer returns success).
    subroutine watch_observe(self, q, v, t, step, stop)
        class(energy_watch_t), intent(inout) :: self  !! the observer
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (3, n)
        real(wp), intent(in), contiguous :: v(:, :)   !! velocities (3, n)
        real(wp), intent(in) :: t                     !! time
        integer(ik), intent(in) :: step               !! steps since init
        logical, intent(inout) :: stop                !! .false. on entry
        real(wp) :: err
        associate (unused_t => t, unused_step => step); end associate
        self%calls = self%calls + 1
        err = abs(plummer_energy(self%model, q, v) / self%e0 - 1.0_wp)
        self%worst = max(self%worst, err)
        if (err > 1.0e-3_wp) stop = .true.
    end subroutine watch_observe
    ! [observe]

end module fsym_guide_model
