!> Splitting schemes as data: an operation code per stage and its coefficients, with metadata
!> (order, forward, symplectic, symmetric, evaluations per step). One constructor per method
!> and family of Chin's paper, a by-name constructor, the catalogue of named members, and a
!> constructor from the user's own arrays that checks consistency.
!>
!> A step of size h runs the stages in order on (q, v):
!>
!> * `OP_DRIFT`        q <- q + c h v
!> * `OP_KICK`         v <- v + c h a(q)
!> * `OP_GRAD_KICK`    v <- v + c h a(q) + u h^3 g(q)   (g: the gradient term, grad |a|^2)
!> * `OP_EXTRAP_KICK`  v <- v + c h a(q + u h^2 a(q))   (the gradient term by extrapolation)
!>
!> The tables know nothing of Hamiltonians: they can drive any pair of flows e^{hT}, e^{hV}.
module fsym_scheme
    use fsym_kinds, only: wp
    use fsym_status
    implicit none
    private

    integer, parameter, public :: OP_DRIFT = 1        !! q <- q + c h v
    integer, parameter, public :: OP_KICK = 2         !! v <- v + c h a(q)
    integer, parameter, public :: OP_GRAD_KICK = 3    !! v <- v + c h a(q) + u h^3 g(q)
    integer, parameter, public :: OP_EXTRAP_KICK = 4  !! v <- v + c h a(q + u h^2 a(q))

    integer, parameter, public :: FSYM_NAME_LEN = 24  !! length of names in the catalogue

    !> One splitting method: its stages and what is known about it.
    type, public :: scheme_t
        character(len=:), allocatable :: name   !! the paper's label, e.g. `A'`, `M2(-0.5)`
        integer :: order = 0                    !! order of accuracy claimed by the table
        integer :: nop = 0                      !! number of stages
        integer, allocatable :: op(:)           !! operation code of each stage (`OP_*`)
        real(wp), allocatable :: c(:)           !! drift or kick weight of each stage
        real(wp), allocatable :: u(:)           !! gradient weight or extrapolation shift, else 0
        logical :: forward = .false.            !! all drift and kick weights >= 0
        logical :: symplectic = .false.         !! symplectic for every force (no extrapolation)
        logical :: symmetric = .false.          !! palindromic table: time-reversible
        logical :: fsal = .false.               !! first and last stage share their force
        integer :: nforce = 0                   !! force evaluations per step (FSAL counted once)
        integer :: ngrad = 0                    !! gradient evaluations per step
    contains
        procedure :: needs_gradient => scheme_needs_gradient
            !! true when any stage is a gradient kick
        procedure :: extrapolated => scheme_extrapolated
            !! the scheme with extrapolated kicks (A -> A')
        procedure :: describe => scheme_describe        !! one text line per stage
        procedure :: min_drift => scheme_min_drift      !! smallest drift weight
        procedure :: min_kick => scheme_min_kick        !! smallest kick weight
    end type scheme_t

    public :: fsym_scheme_custom, fsym_scheme_by_name, fsym_catalogue, fsym_op_name
    public :: fsym_scheme_t2, fsym_scheme_fr, fsym_scheme_a, fsym_scheme_c, fsym_scheme_an
    public :: fsym_scheme_m1, fsym_scheme_m2, fsym_scheme_gfr5, fsym_scheme_t2_product
    public :: fsym_scheme_bm, fsym_scheme_bm_mf, fsym_scheme_srkn6b
    public :: fsym_m1_coefficients, fsym_gfr5_coefficients

    real(wp), parameter :: consistency_tol = 1.0e-12_wp
    real(wp), parameter :: cbrt2 = 1.2599210498948731647672106_wp   ! 2**(1/3)

    ! Blanes & Moan (2002), Table 2, S6 (PRK, position first); see shared/METHODS.md.
    real(wp), parameter :: bm_a1 = 0.0792036964311957_wp, bm_a2 = 0.353172906049774_wp, &
                           bm_a3 = -0.0420650803577195_wp
    real(wp), parameter :: bm_b1 = 0.209515106613362_wp, bm_b2 = -0.143851773179818_wp
    ! Blanes & Moan (2002), Table 3, SRKN6b (momentum first).
    real(wp), parameter :: srkn_b1 = 0.0829844064174052_wp, srkn_b2 = 0.396309801498368_wp, &
                           srkn_b3 = -0.0390563049223486_wp
    real(wp), parameter :: srkn_a1 = 0.245298957184271_wp, srkn_a2 = 0.604872665711080_wp

contains

    ! ---------------------------------------------------------------- user tables and metadata

    !> Build a scheme from the user's own stage arrays, check it and fill in its metadata.
    !> Rejected (non-zero `stat`, `scheme` untouched) when an op code is unknown, a weight is
    !> not finite, or the drift weights or the kick weights do not sum to one.
    subroutine fsym_scheme_custom(name, op, c, u, order, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! label of the method
        integer, intent(in) :: op(:)                    !! operation code per stage (`OP_*`)
        real(wp), intent(in) :: c(:)                    !! drift or kick weight per stage
        real(wp), intent(in) :: u(:)                    !! gradient weight / extrapolation shift
        integer, intent(in) :: order                    !! order the table is meant to have
        type(scheme_t), intent(inout) :: scheme         !! the scheme, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        type(scheme_t) :: s
        real(wp) :: sum_drift, sum_kick
        integer :: k
        character(len=64) :: buf

        if (size(op) < 1 .or. size(c) /= size(op) .or. size(u) /= size(op)) then
            call fsym_report(FSYM_ERR_SHAPE, 'scheme '//trim(name)// &
                             ': op, c and u must have the same non-zero length', stat, errmsg)
            return
        end if
        do k = 1, size(op)
            if (op(k) < OP_DRIFT .or. op(k) > OP_EXTRAP_KICK) then
                write (buf, '(a,i0,a,i0)') 'stage ', k, ' has unknown op code ', op(k)
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                                 trim(buf), stat, errmsg)
                return
            end if
            if (.not. (abs(c(k)) <= huge(1.0_wp) .and. abs(u(k)) <= huge(1.0_wp))) then
                write (buf, '(a,i0,a)') 'stage ', k, ' has a non-finite coefficient'
                call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                                 trim(buf), stat, errmsg)
                return
            end if
        end do
        sum_drift = sum(c, mask=(op == OP_DRIFT))
        sum_kick = sum(c, mask=(op /= OP_DRIFT))
        if (abs(sum_drift - 1.0_wp) > consistency_tol .or. &
            abs(sum_kick - 1.0_wp) > consistency_tol) then
            write (buf, '(a,es12.5,a,es12.5)') 'drifts sum to ', sum_drift, &
                ', kicks to ', sum_kick
            call fsym_report(FSYM_ERR_INCONSISTENT_SCHEME, 'scheme '//trim(name)//': '// &
                             trim(buf)//' (both must be 1)', stat, errmsg)
            return
        end if

        s%name = trim(name)
        s%order = order
        s%nop = size(op)
        s%op = op
        s%c = c
        s%u = u
        where (s%op == OP_DRIFT .or. s%op == OP_KICK) s%u = 0.0_wp
        call fill_metadata(s)
        scheme = s
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_custom

    !> Metadata that follows from the table alone.
    subroutine fill_metadata(s)
        type(scheme_t), intent(inout) :: s
        integer :: k, n
        n = s%nop
        s%forward = all(s%c >= 0.0_wp)
        s%symplectic = .not. any(s%op == OP_EXTRAP_KICK)
        s%symmetric = .true.
        do k = 1, n / 2
            if (s%op(k) /= s%op(n + 1 - k) .or. &
                abs(s%c(k) - s%c(n + 1 - k)) > 1.0e-14_wp * max(1.0_wp, abs(s%c(k))) .or. &
                abs(s%u(k) - s%u(n + 1 - k)) > 1.0e-14_wp * max(1.0_wp, abs(s%u(k)))) then
                s%symmetric = .false.
            end if
        end do
        s%fsal = s%op(1) /= OP_DRIFT .and. s%op(n) /= OP_DRIFT
        call count_evaluations(s%op, s%u, s%nforce, s%ngrad)
    end subroutine fill_metadata

    !> Evaluations per step in steady state, found by running the kernel's cache rules over two
    !> consecutive steps and counting the second: the force at the end of a step is reused by
    !> the next; a drift invalidates every cached quantity.
    pure subroutine count_evaluations(op, u, nforce, ngrad)
        integer, intent(in) :: op(:)
        real(wp), intent(in) :: u(:)
        integer, intent(out) :: nforce, ngrad
        logical :: have_a, have_g, have_x
        real(wp) :: x_shift
        integer :: pass, k
        have_a = .false.; have_g = .false.; have_x = .false.; x_shift = 0.0_wp
        do pass = 1, 2
            nforce = 0; ngrad = 0
            do k = 1, size(op)
                select case (op(k))
                case (OP_DRIFT)
                    have_a = .false.; have_g = .false.; have_x = .false.
                case (OP_KICK)
                    if (.not. have_a) nforce = nforce + 1
                    have_a = .true.
                case (OP_GRAD_KICK)
                    if (.not. have_a) nforce = nforce + 1
                    if (.not. have_g) ngrad = ngrad + 1
                    have_a = .true.; have_g = .true.
                case (OP_EXTRAP_KICK)
                    if (.not. have_a) nforce = nforce + 1
                    if (.not. (have_x .and. x_shift == u(k))) nforce = nforce + 1
                    have_a = .true.; have_x = .true.; x_shift = u(k)
                case default
                    ! op codes are validated when a scheme is built
                end select
            end do
        end do
    end subroutine count_evaluations

    !> True when any stage is a gradient kick.
    pure logical function scheme_needs_gradient(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_needs_gradient = .false.
        if (allocated(self%op)) scheme_needs_gradient = any(self%op == OP_GRAD_KICK)
    end function scheme_needs_gradient

    !> The same scheme with every gradient kick v h (a + (u/v) h^2 g) replaced by the
    !> extrapolated kick v h a(q + (2u/v) h^2 a), which agrees to O(h^5) (paper eq. modfaex);
    !> a prime is added to the name. A scheme without gradient kicks is returned unchanged.
    function scheme_extrapolated(self) result(s)
        class(scheme_t), intent(in) :: self  !! the scheme with gradient kicks
        type(scheme_t) :: s
        integer :: k
        s = self
        if (.not. self%needs_gradient()) return
        do k = 1, s%nop
            if (s%op(k) == OP_GRAD_KICK) then
                s%op(k) = OP_EXTRAP_KICK
                s%u(k) = 2.0_wp * self%u(k) / self%c(k)
            end if
        end do
        s%name = self%name//''''
        call fill_metadata(s)
    end function scheme_extrapolated

    !> Most negative (or smallest) drift weight: how far the method steps backward in position.
    pure real(wp) function scheme_min_drift(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_min_drift = minval(self%c, mask=(self%op == OP_DRIFT))
    end function scheme_min_drift

    !> Smallest kick weight.
    pure real(wp) function scheme_min_kick(self)
        class(scheme_t), intent(in) :: self  !! the scheme
        scheme_min_kick = minval(self%c, mask=(self%op /= OP_DRIFT))
    end function scheme_min_kick

    !> Name of an operation code.
    pure function fsym_op_name(op) result(name)
        integer, intent(in) :: op  !! an `OP_*` code
        character(len=:), allocatable :: name
        select case (op)
        case (OP_DRIFT); name = 'drift'
        case (OP_KICK); name = 'kick'
        case (OP_GRAD_KICK); name = 'gradient-kick'
        case (OP_EXTRAP_KICK); name = 'extrapolated-kick'
        case default; name = 'unknown'
        end select
    end function fsym_op_name

    !> One line per stage: op name, weight, and second coefficient.
    function scheme_describe(self) result(text)
        class(scheme_t), intent(in) :: self  !! the scheme
        character(len=:), allocatable :: text
        character(len=96) :: line
        integer :: k
        text = ''
        do k = 1, self%nop
            write (line, '(i3,1x,a18,2(1x,es24.16))') k, fsym_op_name(self%op(k)), &
                self%c(k), self%u(k)
            text = text//trim(line)//new_line('a')
        end do
    end function scheme_describe

    ! ---------------------------------------------------------------- table helpers

    !> Alternate two kinds of stage, starting and ending with the first: x(1) y(1) x(2) ... x(n).
    !> For the library's own tables, which are consistent by construction.
    subroutine alternate(name, order, first, x, y, s)
        character(len=*), intent(in) :: name
        integer, intent(in) :: order, first
        real(wp), intent(in) :: x(:), y(:)
        type(scheme_t), intent(out) :: s
        call alternating_custom(name, order, first, x, y, s)
    end subroutine alternate

    !> [h(1..m), h(m-1..1)]: a palindrome with a single centre.
    pure function mirror_odd(h) result(p)
        real(wp), intent(in) :: h(:)
        real(wp) :: p(2 * size(h) - 1)
        p(1:size(h)) = h
        p(size(h) + 1:) = h(size(h) - 1:1:-1)
    end function mirror_odd

    !> [h(1..m), h(m..1)]: a palindrome with a doubled centre.
    pure function mirror_even(h) result(p)
        real(wp), intent(in) :: h(:)
        real(wp) :: p(2 * size(h))
        p(1:size(h)) = h
        p(size(h) + 1:) = h(size(h):1:-1)
    end function mirror_even

    !> Real cube root, defined for negative arguments.
    elemental real(wp) function cbrt(x)
        real(wp), intent(in) :: x
        cbrt = sign(abs(x)**(1.0_wp / 3.0_wp), x)
    end function cbrt

    ! ---------------------------------------------------------------- the paper's methods

    !> Second-order leapfrog T2 (paper eq. sec): drift 1/2, kick 1, drift 1/2.
    function fsym_scheme_t2() result(s)
        type(scheme_t) :: s
        call alternate('T2', 2, OP_DRIFT, [0.5_wp, 0.5_wp], [1.0_wp], s)
    end function fsym_scheme_t2

    !> Composition T2(a(1) h) T2(a(2) h) ... T2(a(m) h), adjacent drifts merged; substeps with
    !> a(i) = 0 are dropped. Order 4 when a is symmetric with sum a = 1 and sum a^3 = 0.
    subroutine fsym_scheme_t2_product(name, a, order, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! label
        real(wp), intent(in) :: a(:)                    !! substep fractions
        integer, intent(in) :: order                    !! order claimed
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp), allocatable :: x(:), y(:)
        real(wp) :: nz(size(a))
        integer :: m, k, ops(0)
        m = 0
        do k = 1, size(a)
            if (a(k) /= 0.0_wp) then
                m = m + 1; nz(m) = a(k)
            end if
        end do
        if (m == 0) then
            call fsym_scheme_custom(name, ops, [real(wp) ::], [real(wp) ::], order, scheme, &
                                    stat, errmsg)
            return
        end if
        allocate (x(m + 1), y(m))
        x(1) = 0.5_wp * nz(1)
        do k = 2, m
            x(k) = 0.5_wp * (nz(k - 1) + nz(k))
        end do
        x(m + 1) = 0.5_wp * nz(m)
        y = nz(1:m)
        call alternating_custom(name, order, OP_DRIFT, x, y, scheme, stat, errmsg)
    end subroutine fsym_scheme_t2_product

    !> Like `alternate` but reporting errors to the caller.
    subroutine alternating_custom(name, order, first, x, y, scheme, stat, errmsg)
        character(len=*), intent(in) :: name
        integer, intent(in) :: order, first
        real(wp), intent(in) :: x(:), y(:)
        type(scheme_t), intent(inout) :: scheme
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        integer :: op(size(x) + size(y)), second, k
        real(wp) :: c(size(x) + size(y)), u(size(x) + size(y))
        second = merge(OP_KICK, OP_DRIFT, first == OP_DRIFT)
        do k = 1, size(x)
            op(2 * k - 1) = first; c(2 * k - 1) = x(k)
        end do
        do k = 1, size(y)
            op(2 * k) = second; c(2 * k) = y(k)
        end do
        u = 0.0_wp
        call fsym_scheme_custom(name, op, c, u, order, scheme, stat, errmsg)
    end subroutine alternating_custom

    !> Forest-Ruth (paper eq. fr): T2(a1) T2(a0) T2(a1), a1 = 1/(2 - 2^(1/3)).
    function fsym_scheme_fr() result(s)
        type(scheme_t) :: s
        real(wp) :: a1, a0
        a1 = 1.0_wp / (2.0_wp - cbrt2)
        a0 = -cbrt2 / (2.0_wp - cbrt2)
        call fsym_scheme_t2_product('FR', [a1, a0, a1], 4, s)
    end function fsym_scheme_fr

    !> Forward algorithm A (paper eqs. foura, sima); with `extrapolated`, A' (eq. modfaex).
    function fsym_scheme_a(extrapolated) result(s)
        logical, intent(in), optional :: extrapolated  !! build A' instead of A
        type(scheme_t) :: s
        call fsym_scheme_custom('A', [OP_KICK, OP_DRIFT, OP_GRAD_KICK, OP_DRIFT, OP_KICK], &
                                [1.0_wp / 6.0_wp, 0.5_wp, 2.0_wp / 3.0_wp, 0.5_wp, &
                                 1.0_wp / 6.0_wp], &
                                [0.0_wp, 0.0_wp, (2.0_wp / 3.0_wp) / 48.0_wp, 0.0_wp, 0.0_wp], 4, s)
        if (present(extrapolated)) then
            if (extrapolated) s = s%extrapolated()
        end if
    end function fsym_scheme_a

    !> Forward algorithm C (paper eq. chinc, V-tilde of eq. superv in the central 1/4 kick);
    !> with `extrapolated`, C'.
    function fsym_scheme_c(extrapolated) result(s)
        logical, intent(in), optional :: extrapolated  !! build C' instead of C
        type(scheme_t) :: s
        call fsym_scheme_custom('C', &
            [OP_DRIFT, OP_KICK, OP_DRIFT, OP_GRAD_KICK, OP_DRIFT, OP_KICK, OP_DRIFT], &
            [1.0_wp / 6.0_wp, 3.0_wp / 8.0_wp, 1.0_wp / 3.0_wp, 0.25_wp, 1.0_wp / 3.0_wp, &
             3.0_wp / 8.0_wp, 1.0_wp / 6.0_wp], &
            [0.0_wp, 0.0_wp, 0.0_wp, 0.25_wp / 48.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 4, s)
        if (present(extrapolated)) then
            if (extrapolated) s = s%extrapolated()
        end if
    end function fsym_scheme_c

    !> Forward family AN, N >= 3: N-1 uniform drifts 1/(N-1), N-2 interior kicks
    !> (N-1)/(N(N-2)), end kicks 1/(2N) carrying the gradient eps^2/(24(N-2)) grad|F|^2;
    !> with `extrapolated`, AN' (end force at q + eps^2/(12(N-2)) F(q)).
    subroutine fsym_scheme_an(n, scheme, extrapolated, stat, errmsg)
        integer, intent(in) :: n                        !! number N of the family, >= 3
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        logical, intent(in), optional :: extrapolated   !! build AN' instead of AN
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        type(scheme_t) :: s
        real(wp), allocatable :: x(:), y(:)
        character(len=16) :: label
        integer :: k
        if (n < 3) then
            write (label, '(i0)') n
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'AN needs N >= 3, got N = '//trim(label), &
                             stat, errmsg)
            return
        end if
        allocate (x(n), y(n - 1))
        x(1) = 1.0_wp / (2 * n); x(n) = x(1)      ! kicks: two end kicks, N-2 interior
        do k = 2, n - 1
            x(k) = real(n - 1, wp) / real(n * (n - 2), wp)
        end do
        y = 1.0_wp / (n - 1)                      ! drifts
        write (label, '(a,i0)') 'A', n
        call alternate(trim(label), 4, OP_KICK, x, y, s)
        s%op(1) = OP_GRAD_KICK; s%op(s%nop) = OP_GRAD_KICK
        s%u(1) = s%c(1) / (24.0_wp * (n - 2)); s%u(s%nop) = s%u(1)
        call fill_metadata(s)
        if (present(extrapolated)) then
            if (extrapolated) s = s%extrapolated()
        end if
        scheme = s
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_an

    !> Coefficients (t0, t1, t2, v1, v2) of McLachlan's symmetric four-stage family (paper
    !> eqs. algm1, v2m1/v2m2) for the free parameter t1 < 0. `branch` = +1 gives v2 of eq.
    !> v2m1 (family M1), -1 that of eq. v2m2 (family M2).
    subroutine fsym_m1_coefficients(t1, branch, t0, t2, v1, v2, stat, errmsg)
        real(wp), intent(in) :: t1                      !! free parameter, < 0
        integer, intent(in) :: branch                   !! +1 (M1) or -1 (M2)
        real(wp), intent(out) :: t0, t2, v1, v2         !! the other coefficients
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp) :: w2, r
        character(len=32) :: buf
        t0 = 0.0_wp; t2 = 0.0_wp; v1 = 0.0_wp; v2 = 0.0_wp
        write (buf, '(g0.6)') t1
        if (.not. (t1 < 0.0_wp .and. t1 >= -huge(t1))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'M1/M2 need a finite t1 < 0, got t1 = '// &
                             trim(buf), stat, errmsg)
            return
        end if
        w2 = 3.0_wp - 12.0_wp * t1 + 9.0_wp * t1**2
        r = (9.0_wp * t1 - 4.0_wp + 2.0_wp * sqrt(max(w2, 0.0_wp))) / (3.0_wp * t1)
        if (w2 < 0.0_wp .or. r < 0.0_wp .or. .not. (r <= huge(r))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'M1/M2 have no real root at t1 = '// &
                             trim(buf), stat, errmsg)
            return
        end if
        v2 = 0.25_wp * (1.0_wp + sign(1, branch) * sqrt(r))
        v1 = 0.5_wp - v2
        t2 = 1.0_wp / 6.0_wp - 4.0_wp * t1 * v1**2
        t0 = 1.0_wp - 2.0_wp * (t1 + t2)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_m1_coefficients

    !> Non-forward family M1(t1) (paper eq. algm1 with v2 of eq. v2m1), position first:
    !> drifts t2 t1 t0 t1 t2, kicks v2 v1 v1 v2. McLachlan's member: t1 = (121/3924)(12 - sqrt 471).
    subroutine fsym_scheme_m1(t1, scheme, stat, errmsg, name)
        real(wp), intent(in) :: t1                      !! free parameter, < 0
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=*), intent(in), optional :: name  !! label (default `M1(t1)`)
        call mclachlan_family(t1, +1, OP_DRIFT, family_label('M1', t1, name), scheme, stat, &
                              errmsg)
    end subroutine fsym_scheme_m1

    !> Non-forward family M2(t1) (paper eq. algm2, T and V exchanged, v2 of eq. v2m2), momentum
    !> first: kicks t2 t1 t0 t1 t2, drifts v2 v1 v1 v2.
    subroutine fsym_scheme_m2(t1, scheme, stat, errmsg, name)
        real(wp), intent(in) :: t1                      !! free parameter, < 0
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=*), intent(in), optional :: name  !! label (default `M2(t1)`)
        call mclachlan_family(t1, -1, OP_KICK, family_label('M2', t1, name), scheme, stat, &
                              errmsg)
    end subroutine fsym_scheme_m2

    !> The four-force family of eqs. algm1/algm2: branch +1 with drifts first (M1), branch -1
    !> with kicks first (M2); outer weights t2 t1 t0 t1 t2, inner v2 v1 v1 v2.
    subroutine mclachlan_family(t1, branch, first, label, scheme, stat, errmsg)
        real(wp), intent(in) :: t1
        integer, intent(in) :: branch, first
        character(len=*), intent(in) :: label
        type(scheme_t), intent(inout) :: scheme
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        real(wp) :: t0, t2, v1, v2
        integer :: st
        character(len=256) :: msg
        call fsym_m1_coefficients(t1, branch, t0, t2, v1, v2, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        call alternating_custom(label, 4, first, mirror_odd([t2, t1, t0]), &
                                mirror_even([v2, v1]), scheme, stat, errmsg)
    end subroutine mclachlan_family

    !> Substep fractions (a0, a1, a2) of the five-stage family GFR5(alpha) (paper eq. gfr5).
    subroutine fsym_gfr5_coefficients(alpha, a0, a1, a2, stat, errmsg)
        real(wp), intent(in) :: alpha                   !! free parameter
        real(wp), intent(out) :: a0, a1, a2             !! substep fractions
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp) :: den, root
        character(len=32) :: buf
        a0 = 0.0_wp; a1 = 0.0_wp; a2 = 0.0_wp
        write (buf, '(g0.6)') alpha
        if (.not. (abs(alpha) <= 1.0e6_wp)) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, &
                             'GFR5 needs a finite alpha, |alpha| <= 1e6,'// &
                             ' got '//trim(buf), stat, errmsg)
            return
        end if
        root = cbrt2 * cbrt(1.0_wp + alpha**3)
        den = 2.0_wp * (1.0_wp + alpha) - root
        if (abs(den) <= 1.0e-8_wp * max(1.0_wp, abs(alpha))) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'GFR5 denominator vanishes at alpha = '// &
                             trim(buf)//' (alpha = -1 or alpha^2 + 3 alpha + 1 = 0)', stat, errmsg)
            return
        end if
        a1 = 1.0_wp / den
        a2 = alpha * a1
        a0 = -root * a1
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_gfr5_coefficients

    !> Non-forward family GFR5(alpha) (paper eq. gfr5): T2(a2) T2(a1) T2(a0) T2(a1) T2(a2).
    !> alpha = 0 is Forest-Ruth, alpha = 1 the Creutz-Gocksch/Suzuki method.
    subroutine fsym_scheme_gfr5(alpha, scheme, stat, errmsg, name)
        real(wp), intent(in) :: alpha                   !! free parameter
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=*), intent(in), optional :: name  !! label (default `GFR5(alpha)`)
        real(wp) :: a0, a1, a2
        integer :: st
        character(len=256) :: msg
        call fsym_gfr5_coefficients(alpha, a0, a1, a2, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        call fsym_scheme_t2_product(family_label('GFR5', alpha, name), &
                                    [a2, a1, a0, a1, a2], 4, scheme, stat, errmsg)
    end subroutine fsym_scheme_gfr5

    !> Blanes & Moan S6 in position-first form: 7 drifts, 6 kicks (shared/METHODS.md).
    function fsym_scheme_bm() result(s)
        type(scheme_t) :: s
        real(wp) :: a4, b3
        a4 = 1.0_wp - 2.0_wp * (bm_a1 + bm_a2 + bm_a3)
        b3 = 0.5_wp - (bm_b1 + bm_b2)
        call alternate('BM', 4, OP_DRIFT, mirror_odd([bm_a1, bm_a2, bm_a3, a4]), &
                       mirror_even([bm_b1, bm_b2, b3]), s)
    end function fsym_scheme_bm

    !> Blanes & Moan S6 with the roles swapped (momentum first): 7 kicks, 6 drifts.
    function fsym_scheme_bm_mf() result(s)
        type(scheme_t) :: s
        real(wp) :: a4, b3
        a4 = 1.0_wp - 2.0_wp * (bm_a1 + bm_a2 + bm_a3)
        b3 = 0.5_wp - (bm_b1 + bm_b2)
        call alternate('BM-mf', 4, OP_KICK, mirror_odd([bm_a1, bm_a2, bm_a3, a4]), &
                       mirror_even([bm_b1, bm_b2, b3]), s)
    end function fsym_scheme_bm_mf

    !> Blanes & Moan RKN method SRKN6b (Table 3), momentum first: 7 kicks, 6 drifts.
    function fsym_scheme_srkn6b() result(s)
        type(scheme_t) :: s
        real(wp) :: b4, a3
        b4 = 1.0_wp - 2.0_wp * (srkn_b1 + srkn_b2 + srkn_b3)
        a3 = 0.5_wp - (srkn_a1 + srkn_a2)
        call alternate('SRKN6b', 4, OP_KICK, mirror_odd([srkn_b1, srkn_b2, srkn_b3, b4]), &
                       mirror_even([srkn_a1, srkn_a2, a3]), s)
    end function fsym_scheme_srkn6b

    !> `family(param)` unless the caller named the member.
    function family_label(family, param, name) result(label)
        character(len=*), intent(in) :: family
        real(wp), intent(in) :: param
        character(len=*), intent(in), optional :: name
        character(len=:), allocatable :: label
        character(len=32) :: buf
        if (present(name)) then
            label = trim(name)
        else
            write (buf, '(g0.6)') param
            label = family//'('//trim(adjustl(strip_zeros(buf)))//')'
        end if
    end function family_label

    !> Drop trailing zeros of a decimal number: 0.500000 -> 0.5, -1.00000 -> -1.
    pure function strip_zeros(s) result(r)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: r
        integer :: k
        r = trim(adjustl(s))
        if (index(r, '.') == 0 .or. scan(r, 'eE') > 0) return
        k = len(r)
        do while (k > 1 .and. r(k:k) == '0')
            k = k - 1
        end do
        if (r(k:k) == '.') k = k - 1
        r = r(1:k)
    end function strip_zeros

    ! ---------------------------------------------------------------- names

    !> The named methods of the paper, each reachable through `fsym_scheme_by_name`.
    pure function fsym_catalogue() result(names)
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        names = [character(len=FSYM_NAME_LEN) :: 'T2', 'FR', 'A', 'A''', 'C', 'C''', &
                 'A3', 'A4', 'A5', 'A6', 'A3''', 'A4''', 'A5''', 'A6''', &
                 'M1', 'M1(-1/24)', 'M2(-0.1)', 'M2(-0.5)', 'M2(-1)', 'M2(-2)', &
                 'GFR5(0.3)', 'GFR5(0.5)', 'GFR5(1)', 'BM', 'BM-mf', 'SRKN6b']
    end function fsym_catalogue

    !> Build a scheme from its label, case-insensitive: T2, FR, A, A', C, C', AN and AN'
    !> (N >= 3), M1 (McLachlan's member), M1(t1), M2(t1), GFR5(alpha), BM, BM-mf, SRKN6b.
    !> A prime may be written ', the Unicode prime, or `prime`; a parameter as a decimal
    !> number or a fraction p/q. On error `scheme` is untouched.
    subroutine fsym_scheme_by_name(name, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! method label
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=:), allocatable :: key, base, arg
        logical :: prime, has_arg
        real(wp) :: x
        integer :: n, ios, st, p
        type(scheme_t) :: s
        character(len=256) :: msg

        key = normalize(name)
        prime = .false.
        if (len(key) > 0) prime = key(len(key):len(key)) == ''''
        if (prime) key = key(1:len(key) - 1)
        p = index(key, '(')
        has_arg = p > 0
        if (has_arg) then
            if (key(len(key):len(key)) /= ')') then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(name)//'": missing )', &
                                 stat, errmsg)
                return
            end if
            base = key(1:p - 1)
            arg = key(p + 1:len(key) - 1)
            call parse_real(arg, x, ios)
            if (ios /= 0) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(name)// &
                                 '": cannot read the parameter "'//arg//'"', stat, errmsg)
                return
            end if
        else
            base = key
        end if

        st = FSYM_SUCCESS
        select case (base)
        case ('t2'); s = fsym_scheme_t2()
        case ('fr'); s = fsym_scheme_fr()
        case ('a'); s = fsym_scheme_a()
        case ('c'); s = fsym_scheme_c()
        case ('bm'); s = fsym_scheme_bm()
        case ('bm-mf'); s = fsym_scheme_bm_mf()
        case ('srkn6b'); s = fsym_scheme_srkn6b()
        case ('m1')
            if (has_arg) then
                call fsym_scheme_m1(x, s, st, msg, name=display(name, prime))
            else
                call fsym_scheme_m1((121.0_wp / 3924.0_wp) * (12.0_wp - sqrt(471.0_wp)), s, st, &
                                    msg, name='M1')
            end if
        case ('m2')
            if (.not. has_arg) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(name)// &
                                 '": M2 needs its parameter, e.g. M2(-0.5)', stat, errmsg)
                return
            end if
            call fsym_scheme_m2(x, s, st, msg, name=display(name, prime))
        case ('gfr5')
            if (.not. has_arg) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(name)// &
                                 '": GFR5 needs its parameter, e.g. GFR5(1)', stat, errmsg)
                return
            end if
            call fsym_scheme_gfr5(x, s, st, msg, name=display(name, prime))
        case default
            if (len(base) >= 2 .and. base(1:1) == 'a' .and. verify(base(2:), '0123456789') == 0 &
                .and. .not. has_arg) then
                read (base(2:), *, iostat=ios) n
                if (ios /= 0) n = 0
                call fsym_scheme_an(n, s, stat=st, errmsg=msg)
            else
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(name)// &
                                 '" (known: T2 FR A A'' C C'' AN AN'' M1 M1(t1) M2(t1)'// &
                                 ' GFR5(alpha)'// &
                                 ' BM BM-mf SRKN6b; RKN is not a splitting)', stat, errmsg)
                return
            end if
        end select
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        if (has_arg .and. .not. any(base == [character(len=4) :: 'm1', 'm2', 'gfr5'])) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(name)//'" takes no parameter', &
                             stat, errmsg)
            return
        end if
        if (prime) then
            if (.not. s%needs_gradient()) then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(name)// &
                                 '": only methods with a gradient kick have a primed form', &
                                 stat, errmsg)
                return
            end if
            s = s%extrapolated()
        end if
        scheme = s
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_by_name

    !> The user's label with spaces removed and the prime normalised.
    function display(name, prime) result(d)
        character(len=*), intent(in) :: name
        logical, intent(in) :: prime
        character(len=:), allocatable :: d
        integer :: k
        d = ''
        do k = 1, len_trim(name)
            if (name(k:k) /= ' ') d = d//name(k:k)
        end do
        if (prime) then
            k = scan(d, '''')
            if (k == 0) k = index(d, char(226))
            if (k > 0) d = d(1:k - 1)
        end if
    end function display

    !> Lower case, no blanks, Unicode prime (U+2032) and the word `prime` mapped to '.
    function normalize(name) result(key)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: key
        character(len=3), parameter :: uprime = char(226)//char(128)//char(178)
        integer :: k, p
        key = ''
        do k = 1, len_trim(name)
            select case (name(k:k))
            case (' ')
            case ('A':'Z'); key = key//achar(iachar(name(k:k)) + 32)
            case default; key = key//name(k:k)
            end select
        end do
        do
            p = index(key, uprime)
            if (p == 0) exit
            key = key(1:p - 1)//''''//key(p + 3:)
        end do
        p = index(key, 'prime')
        if (p > 0 .and. p + 4 == len(key)) key = key(1:p - 1)//''''
    end function normalize

    !> Read a decimal number or a fraction p/q.
    subroutine parse_real(text, x, ios)
        character(len=*), intent(in) :: text
        real(wp), intent(out) :: x
        integer, intent(out) :: ios
        real(wp) :: num, den
        integer :: p
        x = 0.0_wp
        ios = 1
        if (len_trim(text) == 0) return
        if (verify(trim(text), '0123456789+-.eEdD/') /= 0) return
        p = index(text, '/')
        if (p > 0) then
            read (text(1:p - 1), *, iostat=ios) num
            if (ios /= 0) return
            read (text(p + 1:), *, iostat=ios) den
            if (ios /= 0) return
            if (den == 0.0_wp) then
                ios = 1; return
            end if
            x = num / den
        else
            read (text, *, iostat=ios) x
            if (ios /= 0) x = 0.0_wp
        end if
    end subroutine parse_real

end module fsym_scheme
