!> Gravitational N-body model in three dimensions: masses m(n), constant G and an optional
!> Plummer softening eps, by direct summation over pairs.
!>
!> Accelerations a_i = sum_{k /= i} G m_k (q_k - q_i) / s_ik^3 with s_ik^2 = |q_k - q_i|^2 +
!> eps^2. The gradient term is g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2; writing
!> f(x) = G x / s(x)^3 (so a_i = sum_k m_k f(q_k - q_i)) and J(x) = df/dx =
!> G (I / s^3 - 3 x x^T / s^5), which is symmetric and even in x, the chain rule gives
!>
!>     g_j = 2 sum_{i /= j} m_i J(q_j - q_i) (a_i - a_j),
!>
!> a sum over pairs like the force itself: for each pair (i, j), w = J(q_j - q_i)(a_i - a_j)
!> adds 2 m_i w to g_j and -2 m_j w to g_i. For unit masses it is the paper's grad |F|^2.
!> The energy is sum_i m_i |v_i|^2 / 2 + V with V = -sum_{i<j} G m_i m_j / s_ij.
!>
!> The explicit-shape procedures (`fsym_nbody_accel`, `fsym_nbody_gradient`,
!> `fsym_nbody_potential`) are the arithmetic; the type only holds the parameters. Their
!> loops are written in a documented order (i ascending, then j > i ascending) so a client
!> that writes the same loop gets the same bits.
module fsym_nbody
    use fsym_kinds, only: wp
    use fsym_status, only: fsym_report, FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_BAD_PARAMETER, &
                           FSYM_ERR_NOT_INITIALIZED
    use fsym_force, only: force_model_t
    implicit none
    private

    !> Newtonian gravity of n bodies in 3D with masses `m`, constant `g` and softening `eps`.
    type, extends(force_model_t), public :: nbody_model_t
        real(wp), allocatable :: m(:)   !! masses (n)
        real(wp) :: g = 1.0_wp          !! gravitational constant
        real(wp) :: eps = 0.0_wp        !! Plummer softening length (0: none)
    contains
        procedure :: acceleration => nbody_acceleration
        procedure :: gradient => nbody_gradient
        procedure :: has_gradient => nbody_has
        procedure :: potential => nbody_potential_tb
        procedure :: has_potential => nbody_has
        procedure :: energy => nbody_energy
        procedure :: init => nbody_init
    end type nbody_model_t

    public :: fsym_nbody_accel, fsym_nbody_gradient, fsym_nbody_potential

contains

    !> Set masses, G and softening. Masses must be positive and finite, G finite and
    !> positive, eps >= 0. On error the model is left as it was.
    subroutine nbody_init(self, m, g, eps, stat, errmsg)
        class(nbody_model_t), intent(inout) :: self           !! the model
        real(wp), intent(in) :: m(:)                          !! masses
        real(wp), intent(in) :: g                             !! gravitational constant
        real(wp), intent(in), optional :: eps                 !! softening length (default 0)
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        real(wp) :: e
        e = 0.0_wp
        if (present(eps)) e = eps
        if (size(m) < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'nbody: need at least one body', stat, errmsg)
            return
        end if
        if (.not. (all(m > 0.0_wp) .and. all(m <= huge(m)))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'nbody: masses must be positive and finite', &
                             stat, errmsg)
            return
        end if
        if (.not. (g > 0.0_wp .and. g <= huge(g) .and. e >= 0.0_wp .and. e <= huge(e))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'nbody: need G > 0 and eps >= 0, finite', &
                             stat, errmsg)
            return
        end if
        self%m = m
        self%g = g
        self%eps = e
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine nbody_init

    !> Accelerations of n bodies by direct summation over pairs (i < j).
    pure subroutine fsym_nbody_accel(n, m, g, eps, q, a)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(out) :: a(3, n)    !! accelerations
        real(wp) :: dx, dy, dz, r2, f, e2
        integer :: i, j
        e2 = eps * eps
        a = 0.0_wp
        do i = 1, n - 1
            do j = i + 1, n
                dx = q(1, j) - q(1, i)
                dy = q(2, j) - q(2, i)
                dz = q(3, j) - q(3, i)
                r2 = dx * dx + dy * dy + dz * dz + e2
                f = g / (r2 * sqrt(r2))
                a(1, i) = a(1, i) + m(j) * f * dx
                a(2, i) = a(2, i) + m(j) * f * dy
                a(3, i) = a(3, i) + m(j) * f * dz
                a(1, j) = a(1, j) - m(i) * f * dx
                a(2, j) = a(2, j) - m(i) * f * dy
                a(3, j) = a(3, j) - m(i) * f * dz
            end do
        end do
    end subroutine fsym_nbody_accel

    !> Gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2, given the accelerations a at q.
    pure subroutine fsym_nbody_gradient(n, m, g, eps, q, a, gt)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(in) :: a(3, n)     !! accelerations at q
        real(wp), intent(out) :: gt(3, n)   !! gradient term
        real(wp) :: x(3), da(3), w(3), r2, rinv2, f, xda
        integer :: i, j
        gt = 0.0_wp
        do i = 1, n - 1
            do j = i + 1, n
                x = q(:, j) - q(:, i)
                r2 = x(1) * x(1) + x(2) * x(2) + x(3) * x(3) + eps * eps
                rinv2 = 1.0_wp / r2
                f = g * rinv2 / sqrt(r2)
                da = a(:, i) - a(:, j)
                xda = x(1) * da(1) + x(2) * da(2) + x(3) * da(3)
                w = f * (da - (3.0_wp * xda * rinv2) * x)
                gt(:, j) = gt(:, j) + (2.0_wp * m(i)) * w
                gt(:, i) = gt(:, i) - (2.0_wp * m(j)) * w
            end do
        end do
    end subroutine fsym_nbody_gradient

    !> Potential energy V = -sum_{i<j} G m_i m_j / s_ij.
    pure real(wp) function fsym_nbody_potential(n, m, g, eps, q) result(epot)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp) :: x(3)
        integer :: i, j
        epot = 0.0_wp
        do i = 1, n - 1
            do j = i + 1, n
                x = q(:, j) - q(:, i)
                epot = epot - g * m(i) * m(j) / sqrt(sum(x**2) + eps * eps)
            end do
        end do
    end function fsym_nbody_potential

    !> Accelerations (q must be (3, size(m))).
    subroutine nbody_acceleration(self, q, a, stat)
        class(nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (3, n)
        real(wp), intent(out), contiguous :: a(:, :)              !! accelerations (3, n)
        integer, intent(inout) :: stat                !! set to FSYM_ERR_SHAPE on a bad shape
        integer :: n
        n = size(q, 2)
        if (.not. allocated(self%m)) then
            stat = FSYM_ERR_NOT_INITIALIZED; a = 0.0_wp; return
        end if
        if (size(q, 1) /= 3 .or. size(self%m) /= n) then
            stat = FSYM_ERR_SHAPE; a = 0.0_wp; return
        end if
        call fsym_nbody_accel(n, self%m, self%g, self%eps, q, a)
    end subroutine nbody_acceleration

    !> Gradient term (see the module description).
    subroutine nbody_gradient(self, q, a, g, stat)
        class(nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (3, n)
        real(wp), intent(in), contiguous :: a(:, :)               !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)              !! gradient term (3, n)
        integer, intent(inout) :: stat                !! set to FSYM_ERR_SHAPE on a bad shape
        integer :: n
        n = size(q, 2)
        if (.not. allocated(self%m)) then
            stat = FSYM_ERR_NOT_INITIALIZED; g = 0.0_wp; return
        end if
        if (size(q, 1) /= 3 .or. size(self%m) /= n) then
            stat = FSYM_ERR_SHAPE; g = 0.0_wp; return
        end if
        call fsym_nbody_gradient(n, self%m, self%g, self%eps, q, a, g)
    end subroutine nbody_gradient

    !> Provided.
    logical function nbody_has(self)
        class(nbody_model_t), intent(in) :: self  !! the model
        nbody_has = allocated(self%m)
    end function nbody_has

    !> Potential energy.
    subroutine nbody_potential_tb(self, q, epot, stat)
        class(nbody_model_t), intent(inout) :: self  !! the model
        real(wp), intent(in), contiguous :: q(:, :)               !! positions (3, n)
        real(wp), intent(out) :: epot                 !! potential energy
        integer, intent(inout) :: stat                !! set on a bad shape
        epot = 0.0_wp
        if (.not. allocated(self%m)) then
            stat = FSYM_ERR_NOT_INITIALIZED; return
        end if
        if (size(q, 1) /= 3 .or. size(q, 2) /= size(self%m)) then
            stat = FSYM_ERR_SHAPE; return
        end if
        epot = fsym_nbody_potential(size(self%m), self%m, self%g, self%eps, q)
    end subroutine nbody_potential_tb

    !> Total energy sum_i m_i |v_i|^2 / 2 + V (velocities v, not momenta).
    real(wp) function nbody_energy(self, q, v) result(e)
        class(nbody_model_t), intent(in) :: self  !! the model
        real(wp), intent(in) :: q(:, :)            !! positions (3, n)
        real(wp), intent(in) :: v(:, :)            !! velocities (3, n)
        integer :: i
        e = 0.0_wp
        if (.not. allocated(self%m)) return
        do i = 1, size(self%m)
            e = e + 0.5_wp * self%m(i) * sum(v(:, i)**2)
        end do
        e = e + fsym_nbody_potential(size(self%m), self%m, self%g, self%eps, q)
    end function nbody_energy

end module fsym_nbody
