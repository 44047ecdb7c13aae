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
!> `fsym_nbody_potential`) are the arithmetic; the type holds the parameters and a work array
!> for its threads.
!>
!> The order of every body's sum (the library's order, whatever the routine, thread count or
!> MPI rank count): the bodies form blocks of FSYM_NBODY_BLOCK (1..128, 129..256, ...); body
!> i's result is ((0 + c(i, 1)) + c(i, 2)) + ... over the blocks J in ascending order, where
!> the partial sum c(i, J) of the terms of the bodies k in J (k /= i) is taken
!>
!> - for J up to and including body i's own block: over k in ascending order;
!> - for a block J after body i's own: in FSYM_NBODY_LANES classes
!>   by mod(k - first body of J, FSYM_NBODY_LANES), each over k in ascending order, then the
!>   class sums added in class order to 0.
!>
!> The symmetric kernel (`fsym_nbody_accel`, `fsym_nbody_gradient`, the model) evaluates
!> each pair once, in tiles (I, J), I <= J: within a tile, body j's sum runs over i in
!> ascending order (one vector lane per j) and body i's, for J after I, in the vector lanes
!> themselves (the classes), so both vectorise without a branch. The per-target range
!> routines (the MPI model's) take the same sums in the same order. With one block
!> (n <= FSYM_NBODY_BLOCK) the order is plain ascending k.
module fsym_nbody
    use fsym_kinds, only: wp, fsym_same
    use fsym_status, only: fsym_report, FSYM_SUCCESS, FSYM_ERR_SHAPE, FSYM_ERR_BAD_ARGUMENT, &
                           FSYM_ERR_NOT_INITIALIZED
    use fsym_force, only: force_model_t
    use fsym_nbody_frequency, only: fsym_nbody_local_frequency
    implicit none
    private

    !> Newtonian gravity of n bodies in 3D with masses `m`, constant `g` and softening `eps`.
    type, extends(force_model_t), public :: nbody_model_t
        real(wp), allocatable :: m(:)   !! masses (n)
        real(wp) :: g = 1.0_wp          !! gravitational constant
        real(wp) :: eps = 0.0_wp        !! Plummer softening length (0: none)
        !> Partial sums of the threaded kernel (3, n, blocks), allocated by `init` in a
        !> library built with OpenMP
        real(wp), allocatable, private :: work(:, :, :)
    contains
        procedure :: acceleration => nbody_acceleration
        procedure :: gradient => nbody_gradient
        procedure :: has_gradient => nbody_has
        procedure :: potential => nbody_potential_tb
        procedure :: has_potential => nbody_has
        procedure :: local_frequency => nbody_frequency
            !! largest pair frequency 2 G (m_i + m_j)/s_ij^3, for the step-size guard
        procedure :: has_frequency => nbody_has
        procedure :: energy => nbody_energy
        procedure :: init => nbody_init
    end type nbody_model_t

    public :: fsym_nbody_accel, fsym_nbody_gradient, fsym_nbody_potential
    public :: fsym_nbody_accel_range, fsym_nbody_gradient_range

    !> Bodies per block of the pair kernel. It fixes the order of every body's sum (blocks of
    !> sources in ascending order, see the module description), so it is a constant.
    integer, parameter, public :: FSYM_NBODY_BLOCK = 128
    !> Largest chunk of targets of the range routines (larger requests are clipped to it; as
    !> a chunk never straddles two blocks, chunks have at most FSYM_NBODY_BLOCK targets).
    integer, parameter, public :: FSYM_NBODY_MAX_BLOCK = 256
    !> Default chunk of targets of the range routines (any chunk gives the same bits).
    integer, parameter :: TARGET_CHUNK = 64
    !> Rows of a tile that go through the inner loop together.
    integer, parameter :: ROWS = 4
    !> Classes of the partial sums c(i, J) for J after body i's block (see the module
    !> description): a fixed part of the order, so a constant.
    integer, parameter, public :: FSYM_NBODY_LANES = 8
    integer, parameter :: LANES = FSYM_NBODY_LANES
    !> Largest work array (reals) that the model allocates for its threads: 3 n nb reals for
    !> n bodies in nb blocks (48 MB at n = 16000); above it the threads use the range routine.
    integer, parameter, public :: FSYM_NBODY_WORK_MAX = 2**25
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
        integer :: nb
        !$ integer :: ast
        e = 0.0_wp
        if (present(eps)) e = eps
        if (size(m) < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'nbody: need at least one body', stat, errmsg)
            return
        end if
        if (.not. (all(m > 0.0_wp) .and. all(m <= huge(m)))) then
            call mass_refusal(m, stat, errmsg)
            return
        end if
        if (.not. (g > 0.0_wp .and. g <= huge(g) .and. e >= 0.0_wp .and. e <= huge(e))) then
            call fsym_report(FSYM_ERR_BAD_ARGUMENT, 'nbody: need G > 0 and eps >= 0, finite', &
                             stat, errmsg)
            return
        end if
        self%m = m
        self%g = g
        self%eps = e
        if (allocated(self%work)) deallocate (self%work)
        nb = (size(m) + FSYM_NBODY_BLOCK - 1) / FSYM_NBODY_BLOCK
        ! the work array serves the threads only: allocated in an OpenMP build (if that
        ! fails, the threads use the range routine: the same bits)
        !$ if (3.0_wp * size(m) * nb <= FSYM_NBODY_WORK_MAX) then
        !$     allocate (self%work(3, size(m), nb), stat=ast)
        !$ end if
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine nbody_init

    !> Accelerations of n bodies by direct summation (all of them, serially, each pair once).
    pure subroutine fsym_nbody_accel(n, m, g, eps, q, a)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(out) :: a(3, n)    !! accelerations
        call pairs_serial(n, m, g, eps * eps, q, a)
    end subroutine fsym_nbody_accel

    !> Gradient term g_j = (1/m_j) d/dq_j sum_i m_i |a_i|^2, given the accelerations a at q
    !> (all bodies, serially, each pair once).
    pure subroutine fsym_nbody_gradient(n, m, g, eps, q, a, gt)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: eps         !! softening length
        real(wp), intent(in) :: q(3, n)     !! positions
        real(wp), intent(in) :: a(3, n)     !! accelerations at q
        real(wp), intent(out) :: gt(3, n)   !! gradient term
        call pairs_serial(n, m, g, eps * eps, q, gt, a)
    end subroutine fsym_nbody_gradient

    !> Accelerations of the target bodies i1..i2 from all n bodies, for a part of the bodies
    !> (the MPI model's own block). Each body's sum is taken in the library's order (blocks
    !> of `FSYM_NBODY_BLOCK` sources in ascending order, each block's partial sum over its
    !> bodies in ascending order, see the module `fsym_nbody` documentation), so the bits are
    !> those of the symmetric kernel of `fsym_nbody_accel` and of the model, whatever the
    !> range. Every interaction (i, k) is evaluated for target i, so a pair whose two bodies
    !> are both targets costs twice what it costs there. Targets go in chunks of `block`
    !> bodies (default 64, at most `FSYM_NBODY_MAX_BLOCK`; no influence on the bits), chunks
    !> over OpenMP threads when the library is built with OpenMP.
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
        integer, intent(in), optional :: block  !! targets per chunk
        call pair_range(n, m, g, eps, q, i1, i2, a, block)
    end subroutine fsym_nbody_accel_range

    !> Gradient term of the target bodies i1..i2 (see the module description), given the
    !> positions and accelerations of all n bodies; order, chunks and threads as in
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
        integer, intent(in), optional :: block  !! targets per chunk
        call pair_range(n, m, g, eps, q, i1, i2, gt, block, a)
    end subroutine fsym_nbody_gradient_range

    !> Chunks of targets i1..i2 over the threads: the accelerations, or with `a` given the
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
        integer, intent(in), optional :: block       !! targets per chunk
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        integer :: nbk, kb, ib, nb, bs, k1, cpb, kk, sub
        logical :: grad
        ! chunks of at most bs targets that never straddle two blocks of the kernel
        bs = TARGET_CHUNK
        if (present(block)) bs = max(1, min(FSYM_NBODY_MAX_BLOCK, block))
        bs = min(bs, FSYM_NBODY_BLOCK)
        cpb = (FSYM_NBODY_BLOCK + bs - 1) / bs
        k1 = (i1 - 1) / FSYM_NBODY_BLOCK
        nbk = ((i2 - 1) / FSYM_NBODY_BLOCK - k1 + 1) * cpb
        grad = present(a)
        !$omp parallel do schedule(dynamic) default(shared) private(kb, ib, nb, kk, sub) &
        !$omp& if(nbk > 1 .and. real(n, wp) * real(i2 - i1 + 1, wp) > FSYM_NBODY_OMP_MIN)
        do kb = 1, nbk
            kk = k1 + (kb - 1) / cpb
            sub = mod(kb - 1, cpb)
            ib = max(i1, kk * FSYM_NBODY_BLOCK + sub * bs + 1)
            nb = min(i2, kk * FSYM_NBODY_BLOCK + min(FSYM_NBODY_BLOCK, (sub + 1) * bs)) - ib + 1
            if (nb < 1) cycle
            if (grad) then
                call gradient_targets(n, m, g, eps * eps, q, a, ib, nb, out(:, ib:ib + nb - 1))
            else
                call accel_targets(n, m, g, eps * eps, q, ib, nb, out(:, ib:ib + nb - 1))
            end if
        end do
        !$omp end parallel do
    end subroutine pair_range

    !> The symmetric kernel on one thread, without a work array: tiles (I, J), I <= J, row by
    !> row (I ascending, then J ascending), each tile's partial sums added to the result at
    !> once. Body b of block K receives c(b, J) for J < K from the tiles (J, K) of the rows
    !> before K, then c(b, K) from the diagonal tile, then c(b, J) for J > K from row K: in
    !> ascending J, the library's order. Accelerations, or the gradient term if `a` is given.
    pure subroutine pairs_serial(n, m, g, e2, q, out, a)
        integer, intent(in) :: n                     !! number of bodies
        real(wp), intent(in) :: m(n)                 !! masses
        real(wp), intent(in) :: g                    !! gravitational constant
        real(wp), intent(in) :: e2                   !! softening length squared
        real(wp), intent(in) :: q(3, n)              !! positions
        real(wp), intent(out) :: out(3, n)           !! accelerations or gradient term
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        real(wp) :: ci(3, FSYM_NBODY_BLOCK), cj(3, FSYM_NBODY_BLOCK)
        integer :: ib, jb, ni, nj
        out = 0.0_wp
        do ib = 1, n, FSYM_NBODY_BLOCK
            ni = min(FSYM_NBODY_BLOCK, n - ib + 1)
            do jb = ib, n, FSYM_NBODY_BLOCK
                nj = min(FSYM_NBODY_BLOCK, n - jb + 1)
                call pair_tile(n, m, g, e2, q, ib, ni, jb, nj, ci, cj, a)
                out(:, ib:ib + ni - 1) = out(:, ib:ib + ni - 1) + ci(:, 1:ni)
                if (jb /= ib) out(:, jb:jb + nj - 1) = out(:, jb:jb + nj - 1) + cj(:, 1:nj)
            end do
        end do
    end subroutine pairs_serial

    !> The symmetric kernel over OpenMP threads: the tiles (I, J), I <= J, go to the threads
    !> as they become free and store their partial sums c(i, J) and c(j, I) in disjoint slots
    !> of the work array w; then each body's result is the sum of its slots in ascending J.
    !> The same additions as `pairs_serial`, so the same bits, for any thread count.
    subroutine pairs_threads(n, m, g, e2, q, out, w, a)
        integer, intent(in) :: n                     !! number of bodies
        real(wp), intent(in) :: m(n)                 !! masses
        real(wp), intent(in) :: g                    !! gravitational constant
        real(wp), intent(in) :: e2                   !! softening length squared
        real(wp), intent(in) :: q(3, n)              !! positions
        real(wp), intent(out) :: out(3, n)           !! accelerations or gradient term
        real(wp), intent(inout) :: w(:, :, :)        !! work array (3, n, number of blocks)
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        integer :: nb, kb, lb, i
        nb = (n + FSYM_NBODY_BLOCK - 1) / FSYM_NBODY_BLOCK
        !$omp parallel default(shared) private(kb, lb, i) &
        !$omp& if(real(n, wp) * real(n, wp) > 2.0_wp * FSYM_NBODY_OMP_MIN)
        !$omp do collapse(2) schedule(dynamic)
        do kb = 1, nb
            do lb = 1, nb
                if (lb >= kb) call tile_to_work(n, m, g, e2, q, kb, lb, w, a)
            end do
        end do
        !$omp end do
        !$omp do schedule(static)
        do i = 1, n
            out(:, i) = 0.0_wp
            do lb = 1, nb
                out(:, i) = out(:, i) + w(:, i, lb)
            end do
        end do
        !$omp end do
        !$omp end parallel
    end subroutine pairs_threads

    !> Tile (kb, lb) of the symmetric kernel into its slots of the work array: c(i, lb) for
    !> i in block kb and, off the diagonal, c(j, kb) for j in block lb.
    pure subroutine tile_to_work(n, m, g, e2, q, kb, lb, w, a)
        integer, intent(in) :: n                     !! number of bodies
        real(wp), intent(in) :: m(n)                 !! masses
        real(wp), intent(in) :: g                    !! gravitational constant
        real(wp), intent(in) :: e2                   !! softening length squared
        real(wp), intent(in) :: q(3, n)              !! positions
        integer, intent(in) :: kb                    !! block I
        integer, intent(in) :: lb                    !! block J >= I
        real(wp), intent(inout) :: w(:, :, :)        !! work array (3, n, number of blocks)
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        real(wp) :: ci(3, FSYM_NBODY_BLOCK), cj(3, FSYM_NBODY_BLOCK)
        integer :: ib, jb, ni, nj
        ib = (kb - 1) * FSYM_NBODY_BLOCK + 1
        jb = (lb - 1) * FSYM_NBODY_BLOCK + 1
        ni = min(FSYM_NBODY_BLOCK, n - ib + 1)
        nj = min(FSYM_NBODY_BLOCK, n - jb + 1)
        call pair_tile(n, m, g, e2, q, ib, ni, jb, nj, ci, cj, a)
        w(:, ib:ib + ni - 1, lb) = ci(:, 1:ni)
        if (lb /= kb) w(:, jb:jb + nj - 1, kb) = cj(:, 1:nj)
    end subroutine tile_to_work

    !> One tile of the symmetric kernel: the pairs (i, j) with i in block I (ib..ib+ni-1)
    !> and j in block J (jb..jb+nj-1), jb >= ib, each evaluated once; the acceleration, or
    !> with `a` given the gradient term. The bodies j are vector lanes; for each i in
    !> ascending order a branch-free vector loop evaluates f and subtracts m_i f (q_j - q_i)
    !> from lane j's accumulator, which thus adds up body j's partial sum c(j, I) over i in
    !> ascending order (into cj): the subtracted term is exactly body j's own term
    !> m_i f (q_i - q_j) negated (IEEE subtraction and multiplication are sign-symmetric and
    !> s_ij = s_ji). Off the diagonal, body i's terms m_j f (q_j - q_i) go to its LANES class
    !> sums (lane j's class), added in class order into c(i, J) (into ci). On the diagonal
    !> (ib = jb) only j > i is visited and body b's sum, in ascending order, starts from its
    !> lane (the terms of i < b) and continues with the terms of j > b (into ci; cj unused).
    !> For the gradient term: x = q_j - q_i, da = a_i - a_j, w = f (da - (3 x.da / s2) x),
    !> f = G / s2 / s; body i's term is -2 m_j w, body j's +2 m_i w (its own term with x and
    !> da negated, so w is).
    pure subroutine pair_tile(n, m, g, e2, q, ib, ni, jb, nj, ci, cj, a)
        integer, intent(in) :: n                                 !! number of bodies
        real(wp), intent(in) :: m(n)                             !! masses
        real(wp), intent(in) :: g                                !! gravitational constant
        real(wp), intent(in) :: e2                               !! softening squared
        real(wp), intent(in) :: q(3, n)                          !! positions
        integer, intent(in) :: ib                                !! first body of block I
        integer, intent(in) :: ni                                !! bodies in block I
        integer, intent(in) :: jb                                !! first body of block J
        integer, intent(in) :: nj                                !! bodies in block J
        real(wp), intent(out) :: ci(3, FSYM_NBODY_BLOCK)         !! c(i, J), i in I
        real(wp), intent(out) :: cj(3, FSYM_NBODY_BLOCK)         !! c(j, I), j in J
        real(wp), intent(in), optional :: a(3, n)                !! accelerations at q
        real(wp) :: tj(FSYM_NBODY_BLOCK, 7), acc(FSYM_NBODY_BLOCK, 3)
        real(wp) :: t(FSYM_NBODY_BLOCK, 3), s(3)
        integer :: li, l, r, i1, i2
        ! block J in lanes: positions, then the mass (acceleration) or a and 2m (gradient)
        do l = 1, nj
            tj(l, 1:3) = q(:, jb + l - 1)
            if (present(a)) then
                tj(l, 4:6) = a(:, jb + l - 1)
                tj(l, 7) = 2.0_wp * m(jb + l - 1)
            else
                tj(l, 4) = m(jb + l - 1)
            end if
        end do
        acc(1:nj, :) = 0.0_wp
        if (ib /= jb) then
            ! off the diagonal: rows in groups, body i's partial sum in LANES classes
            do li = 1, ni, ROWS
                r = min(ROWS, ni - li + 1)
                i1 = ib + li - 1
                i2 = i1 + r - 1
                if (present(a)) then
                    call gradient_rows(r, q(:, i1:i2), a(:, i1:i2), m(i1:i2), g, e2, nj, tj, &
                                       acc, ci(:, li:li + r - 1))
                else
                    call accel_rows(r, q(:, i1:i2), m(i1:i2), g, e2, nj, tj(:, 1:4), acc, &
                                    ci(:, li:li + r - 1))
                end if
            end do
        else
            ! on the diagonal, row by row: body li's sum starts from its lane
            do li = 1, ni
                i1 = ib + li - 1
                if (present(a)) then
                    call gradient_row(q(:, i1), a(:, i1), m(i1), g, e2, li + 1, nj, tj, acc, t)
                else
                    call accel_row(q(:, i1), m(i1), g, e2, li + 1, nj, tj(:, 1:4), acc, t)
                end if
                s = acc(li, :)
                do l = li + 1, nj
                    s(1) = s(1) + t(l, 1)
                    s(2) = s(2) + t(l, 2)
                    s(3) = s(3) + t(l, 3)
                end do
                ci(:, li) = s
            end do
        end if
        do l = 1, nj
            cj(:, l) = acc(l, :)
        end do
    end subroutine pair_tile

    !> Inner loops of the symmetric acceleration kernel off the diagonal: nr <= ROWS bodies i
    !> (at qi, masses mi), in ascending order, against all lanes of block J. Lane j's
    !> accumulator receives -m_i f (q_j - q_i) for each i in turn (ascending i); body i's
    !> terms m_j f (q_j - q_i) go to LANES partial sums by class mod(j - jb, LANES), each in
    !> ascending j, which are then added in class order into c: the library's order for
    !> c(i, J), J after body i's block (a branch-free vector loop over the classes).
    pure subroutine accel_rows(nr, qi, mi, g, e2, nj, tj, acc, c)
        integer, intent(in) :: nr                                !! bodies i
        real(wp), intent(in) :: qi(3, nr)                        !! their positions
        real(wp), intent(in) :: mi(nr)                           !! their masses
        real(wp), intent(in) :: g                                !! gravitational constant
        real(wp), intent(in) :: e2                               !! softening squared
        integer, intent(in) :: nj                                !! lanes
        real(wp), intent(in) :: tj(FSYM_NBODY_BLOCK, 4)          !! positions, masses of J
        real(wp), intent(inout) :: acc(FSYM_NBODY_BLOCK, 3)      !! lanes' partial sums
        real(wp), intent(out) :: c(3, nr)                        !! c(i, J) of the bodies i
        real(wp) :: p(LANES, 3, ROWS), t(FSYM_NBODY_BLOCK, 3), dx, dy, dz, r2, f
        integer :: l0, l, k, r
        p = 0.0_wp
        do l0 = 0, nj - LANES, LANES
            do r = 1, nr
                !GCC$ vector
                do k = 1, LANES
                    l = l0 + k
                    dx = tj(l, 1) - qi(1, r)
                    dy = tj(l, 2) - qi(2, r)
                    dz = tj(l, 3) - qi(3, r)
                    r2 = dx * dx + dy * dy + dz * dz + e2
                    f = g / (r2 * sqrt(r2))
                    p(k, 1, r) = p(k, 1, r) + tj(l, 4) * f * dx
                    p(k, 2, r) = p(k, 2, r) + tj(l, 4) * f * dy
                    p(k, 3, r) = p(k, 3, r) + tj(l, 4) * f * dz
                    acc(l, 1) = acc(l, 1) - mi(r) * f * dx
                    acc(l, 2) = acc(l, 2) - mi(r) * f * dy
                    acc(l, 3) = acc(l, 3) - mi(r) * f * dz
                end do
            end do
        end do
        ! the last lanes (fewer than LANES): the same terms from the row loop
        l0 = nj - mod(nj, LANES)
        do r = 1, nr
            call accel_row(qi(:, r), mi(r), g, e2, l0 + 1, nj, tj, acc, t)
            p(1:nj - l0, :, r) = p(1:nj - l0, :, r) + t(l0 + 1:nj, :)
        end do
        call add_classes(nr, p, c)
    end subroutine accel_rows

    !> c(:, r) = 0 + p(1, :, r) + ... + p(LANES, :, r), in class order, for rows 1..nr.
    pure subroutine add_classes(nr, p, c)
        integer, intent(in) :: nr                                !! rows
        real(wp), intent(in) :: p(LANES, 3, ROWS)                !! class sums
        real(wp), intent(out) :: c(3, nr)                        !! their sums
        integer :: k, r
        c = 0.0_wp
        do r = 1, nr
            do k = 1, LANES
                c(:, r) = c(:, r) + p(k, :, r)
            end do
        end do
    end subroutine add_classes

    !> Inner loop of the symmetric acceleration kernel: body i (at qi, mass mi) against lanes
    !> l0..l1 of block J; body i's terms into t, body j's subtracted from its lane.
    pure subroutine accel_row(qi, mi, g, e2, l0, l1, tj, acc, t)
        real(wp), intent(in) :: qi(3)                            !! position of body i
        real(wp), intent(in) :: mi                               !! its mass
        real(wp), intent(in) :: g                                !! gravitational constant
        real(wp), intent(in) :: e2                               !! softening squared
        integer, intent(in) :: l0                                !! first lane
        integer, intent(in) :: l1                                !! last lane
        real(wp), intent(in) :: tj(FSYM_NBODY_BLOCK, 4)          !! positions, masses of J
        real(wp), intent(inout) :: acc(FSYM_NBODY_BLOCK, 3)      !! lanes' partial sums
        real(wp), intent(inout) :: t(FSYM_NBODY_BLOCK, 3)        !! body i's terms
        real(wp) :: dx, dy, dz, r2, f
        integer :: l
        !GCC$ vector
        do l = l0, l1
            dx = tj(l, 1) - qi(1)
            dy = tj(l, 2) - qi(2)
            dz = tj(l, 3) - qi(3)
            r2 = dx * dx + dy * dy + dz * dz + e2
            f = g / (r2 * sqrt(r2))
            t(l, 1) = tj(l, 4) * f * dx
            t(l, 2) = tj(l, 4) * f * dy
            t(l, 3) = tj(l, 4) * f * dz
            acc(l, 1) = acc(l, 1) - mi * f * dx
            acc(l, 2) = acc(l, 2) - mi * f * dy
            acc(l, 3) = acc(l, 3) - mi * f * dz
        end do
    end subroutine accel_row

    !> Inner loops of the symmetric gradient kernel off the diagonal (as `accel_rows`): nr
    !> bodies i against all lanes of block J; lane j's accumulator receives +2 m_i w for each
    !> i in turn, body i's term -2 m_j w goes to its class sum of lane j.
    pure subroutine gradient_rows(nr, qi, ai, mi, g, e2, nj, tj, acc, c)
        integer, intent(in) :: nr                                !! bodies i
        real(wp), intent(in) :: qi(3, nr)                        !! their positions
        real(wp), intent(in) :: ai(3, nr)                        !! their accelerations
        real(wp), intent(in) :: mi(nr)                           !! their masses
        real(wp), intent(in) :: g                                !! gravitational constant
        real(wp), intent(in) :: e2                               !! softening squared
        integer, intent(in) :: nj                                !! lanes
        real(wp), intent(in) :: tj(FSYM_NBODY_BLOCK, 7)          !! q, a, 2m of block J
        real(wp), intent(inout) :: acc(FSYM_NBODY_BLOCK, 3)      !! lanes' partial sums
        real(wp), intent(out) :: c(3, nr)                        !! c(i, J) of the bodies i
        real(wp) :: p(LANES, 3, ROWS), t(FSYM_NBODY_BLOCK, 3), m2
        real(wp) :: dx, dy, dz, dax, day, daz, r2, rinv2, f, xda, cc, wx, wy, wz
        integer :: l0, l, k, r
        p = 0.0_wp
        do l0 = 0, nj - LANES, LANES
            do r = 1, nr
                m2 = 2.0_wp * mi(r)
                !GCC$ vector
                do k = 1, LANES
                    l = l0 + k
                    dx = tj(l, 1) - qi(1, r)
                    dy = tj(l, 2) - qi(2, r)
                    dz = tj(l, 3) - qi(3, r)
                    r2 = dx * dx + dy * dy + dz * dz + e2
                    rinv2 = 1.0_wp / r2
                    f = g * rinv2 / sqrt(r2)
                    dax = ai(1, r) - tj(l, 4)
                    day = ai(2, r) - tj(l, 5)
                    daz = ai(3, r) - tj(l, 6)
                    xda = dx * dax + dy * day + dz * daz
                    cc = 3.0_wp * xda * rinv2
                    wx = f * (dax - cc * dx)
                    wy = f * (day - cc * dy)
                    wz = f * (daz - cc * dz)
                    p(k, 1, r) = p(k, 1, r) - tj(l, 7) * wx
                    p(k, 2, r) = p(k, 2, r) - tj(l, 7) * wy
                    p(k, 3, r) = p(k, 3, r) - tj(l, 7) * wz
                    acc(l, 1) = acc(l, 1) + m2 * wx
                    acc(l, 2) = acc(l, 2) + m2 * wy
                    acc(l, 3) = acc(l, 3) + m2 * wz
                end do
            end do
        end do
        ! the last lanes (fewer than LANES): the same terms from the row loop
        l0 = nj - mod(nj, LANES)
        do r = 1, nr
            call gradient_row(qi(:, r), ai(:, r), mi(r), g, e2, l0 + 1, nj, tj, acc, t)
            p(1:nj - l0, :, r) = p(1:nj - l0, :, r) + t(l0 + 1:nj, :)
        end do
        call add_classes(nr, p, c)
    end subroutine gradient_rows

    !> Inner loop of the symmetric gradient kernel: body i (position qi, acceleration ai,
    !> mass mi) against lanes l0..l1 of block J; -2 m_j w into t, +2 m_i w onto lane j.
    pure subroutine gradient_row(qi, ai, mi, g, e2, l0, l1, tj, acc, t)
        real(wp), intent(in) :: qi(3)                            !! position of body i
        real(wp), intent(in) :: ai(3)                            !! its acceleration
        real(wp), intent(in) :: mi                               !! its mass
        real(wp), intent(in) :: g                                !! gravitational constant
        real(wp), intent(in) :: e2                               !! softening squared
        integer, intent(in) :: l0                                !! first lane
        integer, intent(in) :: l1                                !! last lane
        real(wp), intent(in) :: tj(FSYM_NBODY_BLOCK, 7)          !! q, a, 2m of block J
        real(wp), intent(inout) :: acc(FSYM_NBODY_BLOCK, 3)      !! lanes' partial sums
        real(wp), intent(inout) :: t(FSYM_NBODY_BLOCK, 3)        !! body i's terms
        real(wp) :: m2, dx, dy, dz, dax, day, daz, r2, rinv2, f, xda, c, wx, wy, wz
        integer :: l
        m2 = 2.0_wp * mi
        !GCC$ vector
        do l = l0, l1
            dx = tj(l, 1) - qi(1)
            dy = tj(l, 2) - qi(2)
            dz = tj(l, 3) - qi(3)
            r2 = dx * dx + dy * dy + dz * dz + e2
            rinv2 = 1.0_wp / r2
            f = g * rinv2 / sqrt(r2)
            dax = ai(1) - tj(l, 4)
            day = ai(2) - tj(l, 5)
            daz = ai(3) - tj(l, 6)
            xda = dx * dax + dy * day + dz * daz
            c = 3.0_wp * xda * rinv2
            wx = f * (dax - c * dx)
            wy = f * (day - c * dy)
            wz = f * (daz - c * dz)
            t(l, 1) = -(tj(l, 7) * wx)
            t(l, 2) = -(tj(l, 7) * wy)
            t(l, 3) = -(tj(l, 7) * wz)
            acc(l, 1) = acc(l, 1) + m2 * wx
            acc(l, 2) = acc(l, 2) + m2 * wy
            acc(l, 3) = acc(l, 3) + m2 * wz
        end do
    end subroutine gradient_row

    !> The per-target acceleration kernel of the range routine: targets ib..ib+nb-1
    !> (nb <= FSYM_NBODY_MAX_BLOCK) against the blocks of FSYM_NBODY_BLOCK sources in
    !> ascending order; per block, the sources in ascending order into a partial sum per
    !> target, which is then added to the target's total. The targets are copied into
    !> contiguous lanes, so the inner loop (`accel_lanes`) runs over lanes without a branch
    !> and vectorises; when a source is itself a target, its lane is left out.
    pure subroutine accel_targets(n, m, g, e2, q, ib, nb, a)
        integer, intent(in) :: n            !! number of bodies
        real(wp), intent(in) :: m(n)        !! masses
        real(wp), intent(in) :: g           !! gravitational constant
        real(wp), intent(in) :: e2          !! softening length squared
        real(wp), intent(in) :: q(3, n)     !! positions
        integer, intent(in) :: ib           !! first target
        integer, intent(in) :: nb           !! number of targets
        real(wp), intent(out) :: a(3, nb)   !! accelerations of the targets
        real(wp) :: ti(FSYM_NBODY_MAX_BLOCK, 3), acc(FSYM_NBODY_MAX_BLOCK, 3)
        real(wp) :: part(FSYM_NBODY_MAX_BLOCK, 3), p(FSYM_NBODY_MAX_BLOCK, 3, LANES)
        integer :: jb, k, l, self
        do l = 1, nb
            ti(l, :) = q(:, ib + l - 1)
        end do
        acc(1:nb, :) = 0.0_wp
        do jb = 1, n, FSYM_NBODY_BLOCK
            part(1:nb, :) = 0.0_wp
            if (jb > ib) then
                ! a block after the targets' block: LANES class sums, added in class order
                p(1:nb, :, :) = 0.0_wp
                do k = jb, min(n, jb + FSYM_NBODY_BLOCK - 1)
                    call accel_lanes(q(:, k), m(k), g, e2, 1, nb, ti, &
                                     p(:, :, mod(k - jb, LANES) + 1))
                end do
                do k = 1, LANES
                    part(1:nb, :) = part(1:nb, :) + p(1:nb, :, k)
                end do
            else
                do k = jb, min(n, jb + FSYM_NBODY_BLOCK - 1)
                    self = k - ib + 1
                    if (self < 1 .or. self > nb) then
                        call accel_lanes(q(:, k), m(k), g, e2, 1, nb, ti, part)
                    else
                        call accel_lanes(q(:, k), m(k), g, e2, 1, self - 1, ti, part)
                        call accel_lanes(q(:, k), m(k), g, e2, self + 1, nb, ti, part)
                    end if
                end do
            end if
            acc(1:nb, :) = acc(1:nb, :) + part(1:nb, :)
        end do
        do l = 1, nb
            a(:, l) = acc(l, :)
        end do
    end subroutine accel_targets

    !> Inner loop of the per-target acceleration kernel: lanes l0..l1 (targets at ti) receive
    !> the attraction of one body at qk with mass mk.
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

    !> The per-target gradient kernel of the range routine, in the order of `accel_targets`:
    !> for target i and source k, x = q_k - q_i, da = a_i - a_k, w = f (da - (3 x.da / s2) x),
    !> f = G / s2 / s and the term -2 m_k w.
    pure subroutine gradient_targets(n, m, g, e2, q, a, ib, nb, gt)
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
        real(wp) :: part(FSYM_NBODY_MAX_BLOCK, 3), p(FSYM_NBODY_MAX_BLOCK, 3, LANES)
        integer :: jb, k, l, self
        do l = 1, nb
            ti(l, 1:3) = q(:, ib + l - 1)
            ti(l, 4:6) = a(:, ib + l - 1)
        end do
        acc(1:nb, :) = 0.0_wp
        do jb = 1, n, FSYM_NBODY_BLOCK
            part(1:nb, :) = 0.0_wp
            if (jb > ib) then
                ! a block after the targets' block: LANES class sums, added in class order
                p(1:nb, :, :) = 0.0_wp
                do k = jb, min(n, jb + FSYM_NBODY_BLOCK - 1)
                    call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, 1, nb, ti, &
                                        p(:, :, mod(k - jb, LANES) + 1))
                end do
                do k = 1, LANES
                    part(1:nb, :) = part(1:nb, :) + p(1:nb, :, k)
                end do
            else
                do k = jb, min(n, jb + FSYM_NBODY_BLOCK - 1)
                    self = k - ib + 1
                    if (self < 1 .or. self > nb) then
                        call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, 1, nb, ti, part)
                    else
                        call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, 1, self - 1, ti, &
                                            part)
                        call gradient_lanes(q(:, k), a(:, k), m(k), g, e2, self + 1, nb, ti, &
                                            part)
                    end if
                end do
            end if
            acc(1:nb, :) = acc(1:nb, :) + part(1:nb, :)
        end do
        do l = 1, nb
            gt(:, l) = acc(l, :)
        end do
    end subroutine gradient_targets

    !> Inner loop of the per-target gradient kernel: lanes l0..l1 (target positions and
    !> accelerations at ti) receive the term of one body at qk with acceleration ak and mass mk.
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
        call model_pairs(self, n, q, a)
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
        call model_pairs(self, n, q, g, a)
    end subroutine nbody_gradient

    !> The model's kernel: symmetric over threads with the work array when there is one,
    !> per target over threads in an OpenMP build without it (too many bodies), symmetric on
    !> one thread otherwise. All three give the same bits.
    subroutine model_pairs(self, n, q, out, a)
        class(nbody_model_t), intent(inout) :: self  !! the model
        integer, intent(in) :: n                     !! number of bodies
        real(wp), intent(in) :: q(3, n)              !! positions
        real(wp), intent(out) :: out(3, n)           !! accelerations or gradient term
        real(wp), intent(in), optional :: a(3, n)    !! accelerations (gradient term wanted)
        logical :: threaded
        threaded = .false.
        !$ threaded = .true.
        if (allocated(self%work)) then
            call pairs_threads(n, self%m, self%g, self%eps * self%eps, q, out, self%work, a)
        else if (threaded) then
            call pair_range(n, self%m, self%g, self%eps, q, 1, n, out, a=a)
        else
            call pairs_serial(n, self%m, self%g, self%eps * self%eps, q, out, a)
        end if
    end subroutine model_pairs

    !> Provided.
    !> The largest local frequency squared over the pairs (`fsym_nbody_local_frequency`) and
    !> the separation where it occurs: the step-size guard's measure of a close encounter.
    subroutine nbody_frequency(self, q, omega2, r, stat)
        class(nbody_model_t), intent(inout) :: self   !! the model
        real(wp), intent(in), contiguous :: q(:, :)   !! positions (3, n)
        real(wp), intent(out) :: omega2               !! largest 2 G (m_i + m_j) / s_ij^3
        real(wp), intent(out) :: r                    !! that pair's separation
        integer, intent(inout) :: stat                !! 1: masses not set for these bodies
        omega2 = 0.0_wp; r = 0.0_wp
        if (.not. allocated(self%m)) then
            stat = 1; return
        end if
        if (size(self%m) /= size(q, 2)) then
            stat = 1; return
        end if
        call fsym_nbody_local_frequency(size(q, 1), size(q, 2), self%m, self%g, self%eps, q, &
                                        omega2, r)
    end subroutine nbody_frequency

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


    !> The refusal of a mass that is not positive and finite, naming the body and saying what
    !> to do for a massless test particle (m = 0: this model requires positive masses).
    subroutine mass_refusal(m, stat, errmsg)
        real(wp), intent(in) :: m(:)
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        character(len=200) :: buf
        integer :: k
        do k = 1, size(m)
            if (.not. (m(k) > 0.0_wp .and. m(k) <= huge(m))) exit
        end do
        k = min(k, size(m))
        if (fsym_same(m(k), 0.0_wp)) then
            write (buf, '(a,i0,a)') 'nbody: body ', k, ' has mass 0; massless test particles '// &
                'are not supported (give it a mass far below the others'')'
        else
            write (buf, '(a,i0,a,es12.5,a)') 'nbody: body ', k, ' has mass ', m(k), &
                '; masses must be positive and finite'
        end if
        call fsym_report(FSYM_ERR_BAD_ARGUMENT, trim(buf), stat, errmsg)
    end subroutine mass_refusal

end module fsym_nbody
