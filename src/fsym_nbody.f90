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
    public :: fsym_nbody_accel_range, fsym_nbody_gradient_range

    !> Targets per block of the pair kernel (any value gives the same bits; this one is fast).
    integer, parameter, public :: FSYM_NBODY_BLOCK = 64
    !> Largest block the pair kernel accepts (larger requests are clipped to it).
    integer, parameter, public :: FSYM_NBODY_MAX_BLOCK = 256
    !> Interactions per call below which the range routines stay on one thread.
    real(wp), parameter :: FSYM_NBODY_OMP_MIN = 1.0e5_wp

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

    !> Accelerations of n bodies by direct summation (all of them, serially).
    pure subroutine fsym_nbody_accel(n, m, g, eps, q, a)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(out) :: a(3, n)    !! accelerations
        integer :: ib, nb
        do ib = 1, n, FSYM_NBODY_BLOCK
            nb = min(FSYM_NBODY_BLOCK, n - ib + 1)
            call accel_block(n, m, g, eps * eps, q, ib, nb, a(:, ib:ib + nb - 1))
        end do
    end subroutine fsym_nbody_accel

    !> Gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2, given the accelerations a at q
    !> (all bodies, serially).
    pure subroutine fsym_nbody_gradient(n, m, g, eps, q, a, gt)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(in) :: a(3, n)     !! accelerations at q
        real(wp), intent(out) :: gt(3, n)   !! gradient term
        integer :: ib, nb
        do ib = 1, n, FSYM_NBODY_BLOCK
            nb = min(FSYM_NBODY_BLOCK, n - ib + 1)
            call gradient_block(n, m, g, eps * eps, q, a, ib, nb, gt(:, ib:ib + nb - 1))
        end do
    end subroutine fsym_nbody_gradient

    !> Accelerations of the target bodies i1..i2 from all n bodies: the one routine that the
    !> model, its threaded form and the MPI model call. Targets go in blocks of `block`
    !> bodies (default `FSYM_NBODY_BLOCK`, at most `FSYM_NBODY_MAX_BLOCK`), blocks over OpenMP
    !> threads when the library is built with OpenMP; every body's sum runs over k = 1..n in
    !> ascending order whatever the block size or thread count, so the bits never change.
    !> Nothing is checked: 1 <= i1 <= i2 <= n is the caller's business.
    subroutine fsym_nbody_accel_range(n, m, g, eps, q, i1, i2, a, block)
        integer, intent(in) :: n                !! number of bodies
        real(wp), intent(in) :: m(n)            !! masses
        real(wp), intent(in) :: g               !! gravitational constant
        real(wp), intent(in) :: eps             !! softening length
        real(wp), intent(in) :: q(3, n)         !! positions of all bodies
        integer, intent(in) :: i1               !! first target body
        integer, intent(in) :: i2               !! last target body
        real(wp), intent(out) :: a(3, i1:i2)    !! accelerations of bodies i1..i2
        integer, intent(in), optional :: block  !! targets per block
        call pair_range(n, m, g, eps, q, i1, i2, a, block)
    end subroutine fsym_nbody_accel_range

    !> Gradient term of the target bodies i1..i2 (see the module description), given the
    !> positions and accelerations of all n bodies; blocks and threads as in
    !> `fsym_nbody_accel_range`, with the same bitwise guarantee.
    subroutine fsym_nbody_gradient_range(n, m, g, eps, q, a, i1, i2, gt, block)
        integer, intent(in) :: n                !! number of bodies
        real(wp), intent(in) :: m(n)            !! masses
        real(wp), intent(in) :: g               !! gravitational constant
        real(wp), intent(in) :: eps             !! softening length
        real(wp), intent(in) :: q(3, n)         !! positions of all bodies
        real(wp), intent(in) :: a(3, n)         !! accelerations of all bodies at q
        integer, intent(in) :: i1               !! first target body
        integer, intent(in) :: i2               !! last target body
        real(wp), intent(out) :: gt(3, i1:i2)   !! gradient term of bodies i1..i2
        integer, intent(in), optional :: block  !! targets per block
        call pair_range(n, m, g, eps, q, i1, i2, gt, block, a)
    end subroutine fsym_nbody_gradient_range

    !> Blocks of targets i1..i2 over the threads: the accelerations, or with `a` given the
    !> gradient term, into `out`.
    subroutine pair_range(n, m, g, eps, q, i1, i2, out, block, a)
        integer, intent(in) :: n                     !! number of bodies
        real(wp), intent(in) :: m(n)                 !! masses
        real(wp), intent(in) :: g                    !! gravitational constant
        real(wp), intent(in) :: eps                  !! softening length
        real(wp), intent(in) :: q(3, n)              !! positions of all bodies
        integer, intent(in) :: i1                    !! first target body
        integer, intent(in) :: i2                    !! last target body
        real(wp), intent(out) :: out(3, i1:i2)       !! result for bodies i1..i2
        integer, intent(in), optional :: block       !! targets per block
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        integer :: nbk, kb, ib, nb, bs
        logical :: grad
        bs = block_size(block)
        nbk = (i2 - i1 + bs) / bs
        grad = present(a)
        !$omp parallel do schedule(dynamic) default(shared) private(kb, ib, nb) &
        !$omp& if(nbk > 1 .and. real(n, wp) * real(i2 - i1 + 1, wp) > FSYM_NBODY_OMP_MIN)
        do kb = 1, nbk
            ib = i1 + (kb - 1) * bs
            nb = min(bs, i2 - ib + 1)
            if (grad) then
                call gradient_block(n, m, g, eps * eps, q, a, ib, nb, out(:, ib:ib + nb - 1))
            else
                call accel_block(n, m, g, eps * eps, q, ib, nb, out(:, ib:ib + nb - 1))
            end if
        end do
        !$omp end parallel do
    end subroutine pair_range

    !> The block size to use: `block` clipped to 1..FSYM_NBODY_MAX_BLOCK, default
    !> FSYM_NBODY_BLOCK.
    pure integer function block_size(block)
        integer, intent(in), optional :: block  !! requested targets per block
        block_size = FSYM_NBODY_BLOCK
        if (present(block)) block_size = max(1, min(FSYM_NBODY_MAX_BLOCK, block))
    end function block_size

    !> The pair kernel for the acceleration: targets ib..ib+nb-1 (nb <= FSYM_NBODY_MAX_BLOCK)
    !> against every body k = 1..n in ascending order. The targets are copied into contiguous
    !> lanes, so the inner loop (`accel_lanes`) runs over lanes without a branch and
    !> vectorises; when k is itself a target, its lane is left out.
    !>
    !> Each term is m_k * f * dx with dx = q_k - q_i, f = G / (s2 sqrt(s2)), added in order
    !> k = 1, 2, ..., n. The symmetric pair loop (i < j, both bodies updated) that this kernel
    !> replaced adds the same terms in the same order per body: its term for k < i is the
    !> exact negative (IEEE subtraction and multiplication are sign-symmetric), subtracted.
    !> So the bits are those of that loop, of any block size and any thread count.
    pure subroutine accel_block(n, m, g, e2, q, ib, nb, a)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: e2          !! softening length squared
        real(wp), intent(in) :: q(3, n)     !! positions
        integer, intent(in) :: ib           !! first target
        integer, intent(in) :: nb           !! number of targets
        real(wp), intent(out) :: a(3, nb)   !! accelerations of the targets
        real(wp) :: ti(FSYM_NBODY_MAX_BLOCK, 3), acc(FSYM_NBODY_MAX_BLOCK, 3)
        integer :: k, l, self
        do l = 1, nb
            ti(l, :) = q(:, ib + l - 1)
        end do
        acc(1:nb, :) = 0.0_wp
        do k = 1, n
            self = k - ib + 1
            if (self < 1 .or. self > nb) then
                call accel_lanes(q(:, k), m(k), g, e2, 1, nb, ti, acc)
            else
                call accel_lanes(q(:, k), m(k), g, e2, 1, self - 1, ti, acc)
                call accel_lanes(q(:, k), m(k), g, e2, self + 1, nb, ti, acc)
            end if
        end do
        do l = 1, nb
            a(:, l) = acc(l, :)
        end do
    end subroutine accel_block

    !> Inner loop of the acceleration kernel: lanes l0..l1 (targets at ti) receive the
    !> attraction of one body at qk with mass mk.
    pure subroutine accel_lanes(qk, mk, g, e2, l0, l1, ti, acc)
        real(wp), intent(in) :: qk(3)                                !! the source body
        real(wp), intent(in) :: mk                                   !! its mass
        real(wp), intent(in) :: g                                    !! gravitational constant
        real(wp), intent(in) :: e2                                   !! softening squared
        integer, intent(in) :: l0                                    !! first lane
        integer, intent(in) :: l1                                    !! last lane
        real(wp), intent(in) :: ti(FSYM_NBODY_MAX_BLOCK, 3)          !! target positions
        real(wp), intent(inout) :: acc(FSYM_NBODY_MAX_BLOCK, 3)      !! accumulated accelerations
        real(wp) :: dx, dy, dz, r2, f
        integer :: l
        !GCC$ vector
        do l = l0, l1
            dx = qk(1) - ti(l, 1)
            dy = qk(2) - ti(l, 2)
            dz = qk(3) - ti(l, 3)
            r2 = dx * dx + dy * dy + dz * dz + e2
            f = g / (r2 * sqrt(r2))
            acc(l, 1) = acc(l, 1) + mk * f * dx
            acc(l, 2) = acc(l, 2) + mk * f * dy
            acc(l, 3) = acc(l, 3) + mk * f * dz
        end do
    end subroutine accel_lanes

    !> The pair kernel for the gradient term: targets ib..ib+nb-1 against every body k = 1..n
    !> in ascending order, with x = q_k - q_i, da = a_i - a_k, w = f (da - (3 x.da / s2) x),
    !> f = G / s2 / s and the term -2 m_k w. As for the acceleration, these are the terms of
    !> the symmetric pair loop (for k < i both x and da change sign, so w does), in its order.
    pure subroutine gradient_block(n, m, g, e2, q, a, ib, nb, gt)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: e2          !! softening length squared
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(in) :: a(3, n)     !! accelerations at q
        integer, intent(in) :: ib           !! first target
        integer, intent(in) :: nb           !! number of targets
        real(wp), intent(out) :: gt(3, nb)  !! gradient term of the targets
        real(wp) :: ti(FSYM_NBODY_MAX_BLOCK, 6), acc(FSYM_NBODY_MAX_BLOCK, 3)
        integer :: k, l, self
        do l = 1, nb
            ti(l, 1:3) = q(:, ib + l - 1)
            ti(l, 4:6) = a(:, ib + l - 1)
        end do
        acc(1:nb, :) = 0.0_wp
        do k = 1, n
            self = k - ib + 1
            if (self < 1 .or. self > nb) then
                call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, 1, nb, ti, acc)
            else
                call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, 1, self - 1, ti, acc)
                call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, self + 1, nb, ti, acc)
            end if
        end do
        do l = 1, nb
            gt(:, l) = acc(l, :)
        end do
    end subroutine gradient_block

    !> Inner loop of the gradient kernel: lanes l0..l1 (target positions and accelerations
    !> at ti) receive the term of one body at qk with acceleration ak and mass mk.
    pure subroutine gradient_lanes(qk, ak, mk, g, e2, l0, l1, ti, acc)
        real(wp), intent(in) :: qk(3)                                !! the source body
        real(wp), intent(in) :: ak(3)                                !! its acceleration
        real(wp), intent(in) :: mk                                   !! its mass
        real(wp), intent(in) :: g                                    !! gravitational constant
        real(wp), intent(in) :: e2                                   !! softening squared
        integer, intent(in) :: l0                                    !! first lane
        integer, intent(in) :: l1                                    !! last lane
        real(wp), intent(in) :: ti(FSYM_NBODY_MAX_BLOCK, 6)          !! target q and a
        real(wp), intent(inout) :: acc(FSYM_NBODY_MAX_BLOCK, 3)      !! accumulated terms
        real(wp) :: m2, dx, dy, dz, dax, day, daz, r2, rinv2, f, xda, c
        integer :: l
        m2 = 2.0_wp * mk
        !GCC$ vector
        do l = l0, l1
            dx = qk(1) - ti(l, 1)
            dy = qk(2) - ti(l, 2)
            dz = qk(3) - ti(l, 3)
            r2 = dx * dx + dy * dy + dz * dz + e2
            rinv2 = 1.0_wp / r2
            f = g * rinv2 / sqrt(r2)
            dax = ti(l, 4) - ak(1)
            day = ti(l, 5) - ak(2)
            daz = ti(l, 6) - ak(3)
            xda = dx * dax + dy * day + dz * daz
            c = 3.0_wp * xda * rinv2
            acc(l, 1) = acc(l, 1) - m2 * (f * (dax - c * dx))
            acc(l, 2) = acc(l, 2) - m2 * (f * (day - c * dy))
            acc(l, 3) = acc(l, 3) - m2 * (f * (daz - c * dz))
        end do
    end subroutine gradient_lanes

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
        call fsym_nbody_accel_range(n, self%m, self%g, self%eps, q, 1, n, a)
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
        call fsym_nbody_gradient_range(n, self%m, self%g, self%eps, q, a, 1, n, g)
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
