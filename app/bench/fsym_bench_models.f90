!> The benchmark's user model: a Kepler force (mu = 1) for independent bodies in any d,
!> written as a user writes a model in the user's own module, an extension of the abstract
!> `force_model_t` (`fsym-bench ratios` runs it as `model=user`).
module fsym_bench_models
    use fsym_kinds, only: wp
    use fsym_force, only: force_model_t
    implicit none
    private

    public :: scale2, scale3

    !> Bodies attracted by a fixed centre of parameter mu, one column of q per body.
    type, extends(force_model_t), public :: user_kepler_t
        real(wp) :: mu = 1.0_wp   !! G M of the centre
    contains
        procedure :: acceleration => user_acceleration  !! -mu q_j/|q_j|^3
        procedure :: gradient => user_gradient          !! 4 mu a_j/|q_j|^3
        procedure :: has_gradient => user_has_gradient  !! true
    end type user_kepler_t

contains

    !> Accelerations of every body: one loop over the bodies, written out for d = 2 and 3
    !> (so that it vectorises), a general loop otherwise.
    subroutine user_acceleration(self, q, a, stat)
        class(user_kepler_t), intent(inout) :: self     !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(out), contiguous :: a(:, :)    !! accelerations (d, n)
        integer, intent(inout) :: stat                  !! unchanged
        associate (unused_stat => stat); end associate   ! not needed here
        call scale_by_r3(-self%mu, q, q, a)
    end subroutine user_acceleration

    !> Gradient term of every body, given the accelerations: 4 mu a_j/|q_j|^3.
    subroutine user_gradient(self, q, a, g, stat)
        class(user_kepler_t), intent(inout) :: self     !! the model
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(in), contiguous :: a(:, :)     !! accelerations at q
        real(wp), intent(out), contiguous :: g(:, :)    !! gradient term (d, n)
        integer, intent(inout) :: stat                  !! unchanged
        associate (unused_stat => stat); end associate   ! not needed here
        call scale_by_r3(4.0_wp * self%mu, q, a, g)
    end subroutine user_gradient

    !> y_j = (f / |q_j|^3) x_j for every body j. As an experienced model writer would: d = 2
    !> and 3 go to loops on explicit-shape arrays, whose leading dimension the compiler
    !> knows (gfortran 12 vectorises the assumed-shape d = 3 loop with 2-lane vectors and
    !> permutations, clearly slower; see `doc/pages/force.md`); d = 2 in blocks.
    pure subroutine scale_by_r3(f, q, x, y)
        real(wp), intent(in) :: f                       !! factor
        real(wp), intent(in), contiguous :: q(:, :)     !! positions (d, n)
        real(wp), intent(in), contiguous :: x(:, :)     !! vectors to scale (d, n)
        real(wp), intent(out), contiguous :: y(:, :)    !! result (d, n)
        real(wp) :: r2
        integer :: j
        select case (size(q, 1))
        case (2)
            call scale2(size(q, 2), f, q, x, y)
        case (3)
            call scale3(size(q, 2), f, q, x, y)
        case default
            do j = 1, size(q, 2)
                r2 = sum(q(:, j)**2)
                y(:, j) = (f / (r2 * sqrt(r2))) * x(:, j)
            end do
        end select
    end subroutine scale_by_r3

    !> `scale_by_r3` in d = 2: a few bodies in one loop; many in blocks, the factors of a
    !> block first, then the products (one loop over the interleaved (x, y) pairs is slower
    !> on arrays that come from L2, as in a step: `fsym-bench loops`, the `d=2` lines).
    pure subroutine scale2(n, f, q, x, y)
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(in) :: f, q(2, n), x(2, n)     !! factor, positions, vectors
        real(wp), intent(out) :: y(2, n)                !! result
        integer, parameter :: nb = 256                  ! bodies per block
        real(wp) :: s(nb), r2
        integer :: j, j0, k
        if (n < 64) then
            do j = 1, n
                r2 = q(1, j)**2 + q(2, j)**2
                s(1) = f / (r2 * sqrt(r2))
                y(1, j) = s(1) * x(1, j); y(2, j) = s(1) * x(2, j)
            end do
            return
        end if
        do j0 = 0, n - 1, nb
            k = min(nb, n - j0)
            do j = 1, k
                s(j) = q(1, j0 + j)**2 + q(2, j0 + j)**2
            end do
            do j = 1, k
                s(j) = f / (s(j) * sqrt(s(j)))
            end do
            do j = 1, k
                y(1, j0 + j) = s(j) * x(1, j0 + j); y(2, j0 + j) = s(j) * x(2, j0 + j)
            end do
        end do
    end subroutine scale2

    !> `scale_by_r3` in d = 3.
    pure subroutine scale3(n, f, q, x, y)
        integer, intent(in) :: n                        !! bodies
        real(wp), intent(in) :: f, q(3, n), x(3, n)     !! factor, positions, vectors
        real(wp), intent(out) :: y(3, n)                !! result
        real(wp) :: r2, s
        integer :: j
        do j = 1, n
            r2 = q(1, j)**2 + q(2, j)**2 + q(3, j)**2
            s = f / (r2 * sqrt(r2))
            y(1, j) = s * x(1, j); y(2, j) = s * x(2, j); y(3, j) = s * x(3, j)
        end do
    end subroutine scale3

    !> The model has the gradient term.
    logical function user_has_gradient(self)
        class(user_kepler_t), intent(in) :: self        !! the model
        associate (unused_self => self); end associate   ! not needed here
        user_has_gradient = .true.
    end function user_has_gradient

end module fsym_bench_models
