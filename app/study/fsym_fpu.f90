!> Chains of unit masses on a line between two fixed walls, joined by springs with potential
!> phi_s(d) = k_s d^2/2 + b_s d^4/4 (d the stretch of spring s = 0..n): the stiff linear
!> chain of the stability study and the stiff Fermi-Pasta-Ulam problem of Hairer, Lubich and
!> Wanner (Geometric Numerical Integration, sec. I.5.1), with the analytic gradient term.
!>
!> FPU in the book's variables: 2m masses q_1..q_2m, q_0 = q_{2m+1} = 0,
!> H = sum p^2/2 + omega^2/4 sum_i (q_{2i} - q_{2i-1})^2 + sum_{i=0}^{m} (q_{2i+1} - q_{2i})^4,
!> so the stiff springs have k = omega^2/2, b = 0 and the soft ones k = 0, b = 4. The book's
!> x/y variables are x_{0,i} = (q_{2i} + q_{2i-1})/sqrt 2, x_{1,i} = (q_{2i} - q_{2i-1})/sqrt 2
!> (y likewise from p); the oscillatory energies are I_j = (y_{1,j}^2 + omega^2 x_{1,j}^2)/2.
module fsym_fpu
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_BAD_PARAMETER, fsym_report
    use fsym_force, only: force_model_t
    implicit none
    private

    !> n unit masses in a row (q(1, 1:n), d = 1), springs s = 0..n with constants k(s), b(s);
    !> spring 0 ties mass 1 to the left wall, spring n ties mass n to the right wall.
    type, extends(force_model_t), public :: spring_chain_model_t
        real(wp), allocatable :: k(:)   !! harmonic constants k(0:n)
        real(wp), allocatable :: b(:)   !! quartic constants b(0:n)
    contains
        procedure :: acceleration => chain_acceleration  !! a = -grad V
        procedure :: gradient => chain_gradient          !! g = grad |a|^2
        procedure :: has_gradient => chain_has           !! true once set up
        procedure :: potential => chain_potential        !! V
        procedure :: has_potential => chain_has          !! true once set up
    end type spring_chain_model_t

    public :: fsym_linear_chain, fsym_fpu_chain, fsym_fpu_initial, fsym_fpu_oscillatory

contains

    !> A linear chain of n masses whose springs alternate soft (constant 1, the wall springs)
    !> and stiff (constant `ratio`): springs 0, 2, 4, ... soft, 1, 3, ... stiff.
    subroutine fsym_linear_chain(n, ratio, model, stat, errmsg)
        integer, intent(in) :: n                             !! number of masses (>= 1)
        real(wp), intent(in) :: ratio                        !! stiff/soft constant (> 0)
        type(spring_chain_model_t), intent(inout) :: model   !! the chain, set on success
        integer, intent(out), optional :: stat               !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: s
        if (n < 1 .or. .not. (ratio > 0.0_wp .and. ratio <= huge(ratio))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'linear chain needs n >= 1 and a finite '// &
                             'ratio > 0', stat, errmsg)
            return
        end if
        model%k = [(merge(1.0_wp, ratio, mod(s, 2) == 0), s = 0, n)]
        model%b = [(0.0_wp, s = 0, n)]
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_linear_chain

    !> The FPU chain with m stiff/soft pairs (2m masses) and stiff frequency omega.
    subroutine fsym_fpu_chain(m, omega, model, stat, errmsg)
        integer, intent(in) :: m                             !! number of stiff springs (>= 1)
        real(wp), intent(in) :: omega                        !! stiff frequency (> 0)
        type(spring_chain_model_t), intent(inout) :: model   !! the chain, set on success
        integer, intent(out), optional :: stat               !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        integer :: s
        if (m < 1 .or. .not. (omega > 0.0_wp .and. omega <= huge(omega))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'FPU chain needs m >= 1 and a finite '// &
                             'omega > 0', stat, errmsg)
            return
        end if
        model%k = [(merge(0.5_wp * omega**2, 0.0_wp, mod(s, 2) == 1), s = 0, 2 * m)]
        model%b = [(merge(0.0_wp, 4.0_wp, mod(s, 2) == 1), s = 0, 2 * m)]
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_fpu_chain

    !> Initial values of the book: x_{0,1} = 1, y_{0,1} = 1, x_{1,1} = 1/omega, y_{1,1} = 1,
    !> all others zero, returned in the chain variables q(1, 2m), v(1, 2m).
    pure subroutine fsym_fpu_initial(omega, q, v)
        real(wp), intent(in) :: omega    !! stiff frequency
        real(wp), intent(out) :: q(:, :) !! positions (1, 2m)
        real(wp), intent(out) :: v(:, :) !! velocities (1, 2m)
        real(wp), parameter :: r = 0.70710678118654752440_wp   ! 1/sqrt(2)
        real(wp) :: x0, x1, y0, y1
        q = 0.0_wp; v = 0.0_wp
        x0 = 1.0_wp; x1 = 1.0_wp / omega; y0 = 1.0_wp; y1 = 1.0_wp
        ! q_{2i-1} = (x0 - x1)/sqrt 2, q_{2i} = (x0 + x1)/sqrt 2 for i = 1
        q(1, 1) = r * (x0 - x1); q(1, 2) = r * (x0 + x1)
        v(1, 1) = r * (y0 - y1); v(1, 2) = r * (y0 + y1)
    end subroutine fsym_fpu_initial

    !> Oscillatory energies I_j = (y_{1,j}^2 + omega^2 x_{1,j}^2)/2 of the m stiff springs.
    pure subroutine fsym_fpu_oscillatory(omega, q, v, energy)
        real(wp), intent(in) :: omega      !! stiff frequency
        real(wp), intent(in) :: q(:, :)    !! positions (1, 2m)
        real(wp), intent(in) :: v(:, :)    !! velocities (1, 2m)
        real(wp), intent(out) :: energy(:) !! I_1..I_m
        real(wp), parameter :: r = 0.70710678118654752440_wp
        real(wp) :: x1, y1
        integer :: j
        do j = 1, size(energy)
            x1 = r * (q(1, 2 * j) - q(1, 2 * j - 1))
            y1 = r * (v(1, 2 * j) - v(1, 2 * j - 1))
            energy(j) = 0.5_wp * (y1**2 + omega**2 * x1**2)
        end do
    end subroutine fsym_fpu_oscillatory

    !> Stretch of spring s of the row z (walls fixed at zero).
    pure real(wp) function stretch(z, s)
        real(wp), intent(in) :: z(:)
        integer, intent(in) :: s
        real(wp) :: left, right
        left = 0.0_wp; right = 0.0_wp
        if (s >= 1) left = z(s)
        if (s < size(z)) right = z(s + 1)
        stretch = right - left
    end function stretch

    !> a_j = phi'_j(d_j) - phi'_{j-1}(d_{j-1}).
    subroutine chain_acceleration(self, q, a, stat)
        class(spring_chain_model_t), intent(inout) :: self  !! the chain
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (1, n)
        real(wp), intent(out), contiguous :: a(:, :)                     !! accelerations (1, n)
        integer, intent(inout) :: stat                       !! 1 when unset or the shape is wrong
        integer :: s, n, left, right
        real(wp) :: d, f
        n = size(q, 2)
        if (.not. chain_ready(self, q)) then
            a = 0.0_wp; stat = 1; return
        end if
        a = 0.0_wp
        do s = 0, n   ! spring s joins masses s (left) and s + 1 (right); 0 and n + 1 are walls
            d = stretch(q(1, :), s)
            f = self%k(s + 1) * d + self%b(s + 1) * d**3
            left = s; right = s + 1
            if (left >= 1) a(1, left) = a(1, left) + f
            if (right <= n) a(1, right) = a(1, right) - f
        end do
    end subroutine chain_acceleration

    !> g = grad |a|^2 = -2 H a, H the Hessian of the potential:
    !> (H w)_j = phi''_{j-1} (w_j - w_{j-1}) - phi''_j (w_{j+1} - w_j).
    subroutine chain_gradient(self, q, a, g, stat)
        class(spring_chain_model_t), intent(inout) :: self  !! the chain
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (1, n)
        real(wp), intent(in), contiguous :: a(:, :)                      !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)                     !! gradient term (1, n)
        integer, intent(inout) :: stat                       !! 1 when unset or the shape is wrong
        integer :: s, n, left, right
        real(wp) :: d, f
        n = size(q, 2)
        if (.not. chain_ready(self, q)) then
            g = 0.0_wp; stat = 1; return
        end if
        g = 0.0_wp
        do s = 0, n
            d = stretch(q(1, :), s)
            f = (self%k(s + 1) + 3.0_wp * self%b(s + 1) * d**2) * stretch(a(1, :), s)
            ! H a gets -f at the spring's left mass and +f at its right mass; g = -2 H a
            left = s; right = s + 1
            if (left >= 1) g(1, left) = g(1, left) + 2.0_wp * f
            if (right <= n) g(1, right) = g(1, right) - 2.0_wp * f
        end do
    end subroutine chain_gradient

    !> The chain is set up (`fsym_linear_chain`, `fsym_fpu_chain`) and q has its shape (1, n):
    !> an unset chain is refused with stat = 1, never used.
    logical function chain_ready(self, q)
        class(spring_chain_model_t), intent(in) :: self  !! the chain
        real(wp), intent(in) :: q(:, :)                   !! positions
        chain_ready = .false.
        if (.not. (allocated(self%k) .and. allocated(self%b))) return
        chain_ready = size(q, 1) == 1 .and. size(self%k) == size(q, 2) + 1 .and. &
                      size(self%b) == size(q, 2) + 1
    end function chain_ready

    !> Provided.
    logical function chain_has(self)
        class(spring_chain_model_t), intent(in) :: self  !! the chain
        chain_has = allocated(self%k)
    end function chain_has

    !> sum_s k_s d_s^2/2 + b_s d_s^4/4.
    subroutine chain_potential(self, q, epot, stat)
        class(spring_chain_model_t), intent(inout) :: self  !! the chain
        real(wp), intent(in), contiguous :: q(:, :)                      !! positions (1, n)
        real(wp), intent(out) :: epot                        !! potential energy
        integer, intent(inout) :: stat                       !! 1 when unset or the shape is wrong
        integer :: s, n
        real(wp) :: d
        n = size(q, 2)
        epot = 0.0_wp
        if (.not. chain_ready(self, q)) then
            stat = 1; return
        end if
        do s = 0, n
            d = stretch(q(1, :), s)
            epot = epot + 0.5_wp * self%k(s + 1) * d**2 + 0.25_wp * self%b(s + 1) * d**4
        end do
    end subroutine chain_potential

end module fsym_fpu
