!> The paper's methods and families as stage tables, the catalogue of named members
!> (`fsym_catalogue()`) and the label parser `fsym_scheme_by_name`. (The module is not called
!> `fsym_catalogue`: a module may not share its name with the function it exports.)
!>
!> Specification: S. A. Chin, *Forward and non-forward symplectic integrators in solving
!> classical dynamics problems*, Int. J. Comput. Math. 84(6), 729-747 (2007),
!> doi:10.1080/00207160701458476, arXiv:0704.3273 ("the paper" below; equation names are
!> the labels of its LaTeX source). Coefficient sources:
!>
!> * T2, FR, GFR5: E. Forest and R. D. Ruth, *Fourth-order symplectic integration*, Physica D
!>   43(1), 105-117 (1990), doi:10.1016/0167-2789(90)90019-L; the GFR5 member alpha = 1 is
!>   M. Creutz and A. Gocksch, *Higher-order hybrid Monte Carlo algorithms*, Phys. Rev. Lett.
!>   63(1), 9-12 (1989), doi:10.1103/PhysRevLett.63.9, and M. Suzuki, *Fractal decomposition
!>   of exponential operators with applications to many-body theories and Monte Carlo
!>   simulations*, Phys. Lett. A 146(6), 319-323 (1990), doi:10.1016/0375-9601(90)90962-N.
!> * A, C (and A', C'): S. A. Chin, *Symplectic integrators from composite operator
!>   factorizations*, Phys. Lett. A 226(6), 344-348 (1997), doi:10.1016/S0375-9601(97)00003-0,
!>   as written in the paper (eqs. foura, sima, chinc, superv, modfaex); AN: the paper's
!>   forward family with N - 1 forces and one gradient.
!> * M1, M2: R. I. McLachlan, *On the numerical integration of ordinary differential
!>   equations by symmetric composition methods*, SIAM J. Sci. Comput. 16(1), 151-168 (1995),
!>   doi:10.1137/0916010, in the paper's parametrisation (eqs. algm1, algm2, v2m1, v2m2).
!> * BM, BM-mf, SRKN6b: S. Blanes and P. C. Moan, *Practical symplectic partitioned
!>   Runge-Kutta and Runge-Kutta-Nystrom methods*, J. Comput. Appl. Math. 142(2), 313-330
!>   (2002), doi:10.1016/S0377-0427(01)00492-7, Table 2 (S6) and Table 3 (SRKN6b).
!> * Gradient (force-gradient) kicks in general: I. P. Omelyan, I. M. Mryglod and R. Folk,
!>   *Optimized Verlet-like algorithms for molecular dynamics simulations*, Phys. Rev. E 65,
!>   056706 (2002), doi:10.1103/PhysRevE.65.056706, and *Symplectic analytically integrable
!>   decomposition algorithms: classification, derivation, and application to molecular
!>   dynamics, quantum and celestial mechanics simulations*, Comput. Phys. Commun. 151(3),
!>   272-314 (2003), doi:10.1016/S0010-4655(02)00754-3.
!>
!> Label limits (each refused with a status and a message, never by stopping): a label has at
!> most `FSYM_LABEL_LEN` characters once blanks are removed; AN takes 3 <= N <= `FSYM_AN_MAX`;
!> a family parameter must be a finite decimal number or fraction p/q with q /= 0, inside the
!> family's domain. Every array is allocated with `stat=`; the parser works in fixed-length
!> buffers and is thread-safe.
module fsym_paper_schemes
    use fsym_kinds, only: wp
    use fsym_status, only: FSYM_SUCCESS, FSYM_ERR_UNKNOWN_METHOD, FSYM_ERR_BAD_PARAMETER, &
                           FSYM_ERR_NO_MEMORY, fsym_report, fsym_pass
    use fsym_scheme, only: scheme_t, OP_DRIFT, OP_KICK, OP_GRAD_KICK, OP_EXTRAP_KICK, &
                           fsym_scheme_custom, fsym_scheme_extrapolate, fsym_scheme_take
    implicit none
    private

    integer, parameter, public :: FSYM_NAME_LEN = 24
        !! length of the names in the catalogue
    integer, parameter, public :: FSYM_LABEL_LEN = 64
        !! longest label `fsym_scheme_by_name` reads (blanks removed, a prime counted once)
    integer, parameter, public :: FSYM_AN_MAX = 1000
        !! largest N of the AN family (1999 stages; beyond it the drifts no longer sum to one
        !! within the table check's 1e-12, and the method has no use)

    public :: fsym_scheme_by_name, fsym_catalogue
    public :: fsym_scheme_t2, fsym_scheme_fr, fsym_scheme_a, fsym_scheme_c, fsym_scheme_an
    public :: fsym_scheme_m1, fsym_scheme_m2, fsym_scheme_gfr5, fsym_scheme_t2_product
    public :: fsym_scheme_bm, fsym_scheme_bm_mf, fsym_scheme_srkn6b
    public :: fsym_m1_coefficients, fsym_gfr5_coefficients

    real(wp), parameter :: cbrt2 = 1.2599210498948731647672106_wp   ! 2**(1/3)

    ! Blanes & Moan (2002), Table 2, S6 (partitioned RK, position first).
    real(wp), parameter :: bm_a1 = 0.0792036964311957_wp, bm_a2 = 0.353172906049774_wp, &
                           bm_a3 = -0.0420650803577195_wp
    real(wp), parameter :: bm_b1 = 0.209515106613362_wp, bm_b2 = -0.143851773179818_wp
    ! Blanes & Moan (2002), Table 3, SRKN6b (momentum first).
    real(wp), parameter :: srkn_b1 = 0.0829844064174052_wp, srkn_b2 = 0.396309801498368_wp, &
                           srkn_b3 = -0.0390563049223486_wp
    real(wp), parameter :: srkn_a1 = 0.245298957184271_wp, srkn_a2 = 0.604872665711080_wp

    !> Length of a label as shown in messages (the first `FSYM_LABEL_LEN` characters and `...`).
    integer, parameter :: shown_len = FSYM_LABEL_LEN + 3

contains

    ! ---------------------------------------------------------------- table helpers

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

    !> Alternate two kinds of stage, starting and ending with the first: x(1) y(1) x(2) ... x(n),
    !> and hand the table to `fsym_scheme_custom`.
    subroutine alternating_custom(name, order, first, x, y, scheme, stat, errmsg)
        character(len=*), intent(in) :: name
        integer, intent(in) :: order, first
        real(wp), intent(in) :: x(:), y(:)
        type(scheme_t), intent(inout) :: scheme
        integer, intent(out), optional :: stat
        character(len=*), intent(inout), optional :: errmsg
        integer, allocatable :: op(:)
        real(wp), allocatable :: c(:), u(:)
        integer :: second, k, ist
        allocate (op(size(x) + size(y)), stat=ist)
        if (ist == 0) allocate (c(size(x) + size(y)), stat=ist)
        if (ist == 0) allocate (u(size(x) + size(y)), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'scheme '//trim(name)//': stage table', &
                             stat, errmsg)
            return
        end if
        second = merge(OP_KICK, OP_DRIFT, first == OP_DRIFT)
        do k = 1, size(x)
            op(2 * k - 1) = first; c(2 * k - 1) = x(k)
        end do
        do k = 1, size(y)
            op(2 * k) = second; c(2 * k) = y(k)
        end do
        u(:) = 0.0_wp
        call fsym_scheme_custom(name, op, c, u, order, scheme, stat, errmsg)
    end subroutine alternating_custom

    ! ---------------------------------------------------------------- the paper's methods

    !> Second-order leapfrog T2 (paper eq. sec): drift 1/2, kick 1, drift 1/2.
    function fsym_scheme_t2() result(s)
        type(scheme_t) :: s
        integer :: st
        call alternating_custom('T2', 2, OP_DRIFT, [0.5_wp, 0.5_wp], [1.0_wp], s, st)
    end function fsym_scheme_t2

    !> Composition T2(a(1) h) T2(a(2) h) ... T2(a(m) h), adjacent drifts merged; substeps with
    !> a(i) = 0 are dropped. Order 4 when a is symmetric with sum a = 1 and sum a^3 = 0
    !> (Creutz & Gocksch 1989, Suzuki 1990, Forest & Ruth 1990).
    subroutine fsym_scheme_t2_product(name, a, order, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! label
        real(wp), intent(in) :: a(:)                    !! substep fractions
        integer, intent(in) :: order                    !! order claimed
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        real(wp), allocatable :: x(:), y(:)
        integer :: m, k, ist, ops(0)
        ! a /= 0, written without == or /= on reals (no -Wcompare-reals; NaN counts)
        m = count(.not. (a <= 0.0_wp .and. a >= 0.0_wp))
        if (m == 0) then
            call fsym_scheme_custom(name, ops, [real(wp) ::], [real(wp) ::], order, scheme, &
                                    stat, errmsg)
            return
        end if
        allocate (x(m + 1), stat=ist)
        if (ist == 0) allocate (y(m), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'scheme '//trim(name)//': stage table', &
                             stat, errmsg)
            return
        end if
        y(:) = pack(a, .not. (a <= 0.0_wp .and. a >= 0.0_wp))
        x(1) = 0.5_wp * y(1)
        do k = 2, m
            x(k) = 0.5_wp * (y(k - 1) + y(k))
        end do
        x(m + 1) = 0.5_wp * y(m)
        call alternating_custom(name, order, OP_DRIFT, x, y, scheme, stat, errmsg)
    end subroutine fsym_scheme_t2_product

    !> Forest-Ruth (paper eq. fr): T2(a1) T2(a0) T2(a1), a1 = 1/(2 - 2^(1/3)).
    function fsym_scheme_fr() result(s)
        type(scheme_t) :: s
        integer :: st
        call build_fr(s, st)
    end function fsym_scheme_fr

    subroutine build_fr(s, st)
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        real(wp) :: a1, a0
        a1 = 1.0_wp / (2.0_wp - cbrt2)
        a0 = -cbrt2 / (2.0_wp - cbrt2)
        call fsym_scheme_t2_product('FR', [a1, a0, a1], 4, s, st)
    end subroutine build_fr

    !> Forward algorithm A (paper eqs. foura, sima); with `extrapolated`, A' (eq. modfaex).
    function fsym_scheme_a(extrapolated) result(s)
        logical, intent(in), optional :: extrapolated  !! build A' instead of A
        type(scheme_t) :: s
        integer :: st
        call build_a(s, st)
        call prime_if(s, st, extrapolated)
    end function fsym_scheme_a

    subroutine build_a(s, st)
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        call fsym_scheme_custom('A', [OP_KICK, OP_DRIFT, OP_GRAD_KICK, OP_DRIFT, OP_KICK], &
                                [1.0_wp / 6.0_wp, 0.5_wp, 2.0_wp / 3.0_wp, 0.5_wp, &
                                 1.0_wp / 6.0_wp], &
                                [0.0_wp, 0.0_wp, (2.0_wp / 3.0_wp) / 48.0_wp, 0.0_wp, 0.0_wp], &
                                4, s, st)
    end subroutine build_a

    !> Forward algorithm C (paper eq. chinc, V-tilde of eq. superv in the central 1/4 kick);
    !> with `extrapolated`, C'.
    function fsym_scheme_c(extrapolated) result(s)
        logical, intent(in), optional :: extrapolated  !! build C' instead of C
        type(scheme_t) :: s
        integer :: st
        call build_c(s, st)
        call prime_if(s, st, extrapolated)
    end function fsym_scheme_c

    subroutine build_c(s, st)
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        call fsym_scheme_custom('C', &
            [OP_DRIFT, OP_KICK, OP_DRIFT, OP_GRAD_KICK, OP_DRIFT, OP_KICK, OP_DRIFT], &
            [1.0_wp / 6.0_wp, 3.0_wp / 8.0_wp, 1.0_wp / 3.0_wp, 0.25_wp, 1.0_wp / 3.0_wp, &
             3.0_wp / 8.0_wp, 1.0_wp / 6.0_wp], &
            [0.0_wp, 0.0_wp, 0.0_wp, 0.25_wp / 48.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], 4, s, st)
    end subroutine build_c

    !> Forward family AN, 3 <= N <= `FSYM_AN_MAX` (the paper's family after eq. gfr5): N-1
    !> uniform drifts 1/(N-1), N-2 interior kicks (N-1)/(N(N-2)), end kicks 1/(2N) carrying
    !> the gradient eps^2/(24(N-2)) grad|F|^2; with `extrapolated`, AN' (end force at
    !> q + eps^2/(12(N-2)) F(q)). N outside the range gives `FSYM_ERR_BAD_PARAMETER`.
    subroutine fsym_scheme_an(n, scheme, extrapolated, stat, errmsg)
        integer, intent(in) :: n                        !! number N of the family
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        logical, intent(in), optional :: extrapolated   !! build AN' instead of AN
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        type(scheme_t) :: s
        integer, allocatable :: op(:)
        real(wp), allocatable :: c(:), u(:)
        character(len=16) :: label
        integer :: k, ist, st, ns
        character(len=256) :: msg
        if (n < 3 .or. n > FSYM_AN_MAX) then
            write (label, '(i0)') n
            call fsym_report(FSYM_ERR_BAD_PARAMETER, 'AN needs N >= 3 and N <= '// &
                             trim(an_max_text())//', got N = '//trim(label), stat, errmsg)
            return
        end if
        ns = 2 * n - 1
        allocate (op(ns), stat=ist)
        if (ist == 0) allocate (c(ns), stat=ist)
        if (ist == 0) allocate (u(ns), stat=ist)
        if (ist /= 0) then
            call fsym_report(FSYM_ERR_NO_MEMORY, 'AN stage table', stat, errmsg)
            return
        end if
        ! kicks at the odd stages (two end kicks, N-2 interior), drifts at the even ones
        c(1) = 1.0_wp / (2 * n)
        do k = 2, n - 1
            c(2 * k - 1) = real(n - 1, wp) / real(n * (n - 2), wp)
        end do
        c(ns) = c(1)
        op(1:ns:2) = OP_KICK
        op(2:ns:2) = OP_DRIFT
        c(2:ns:2) = 1.0_wp / (n - 1)
        u(:) = 0.0_wp
        op(1) = OP_GRAD_KICK; op(ns) = OP_GRAD_KICK
        u(1) = c(1) / (24.0_wp * (n - 2)); u(ns) = u(1)
        write (label, '(a,i0)') 'A', n
        call fsym_scheme_custom(trim(label), op, c, u, 4, s, st, msg)
        call prime_if(s, st, extrapolated, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        call fsym_scheme_take(s, scheme)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_an

    !> Replace `s` by its extrapolated form when `extrapolated` is present and true and `st`
    !> says that `s` was built.
    subroutine prime_if(s, st, extrapolated, msg)
        type(scheme_t), intent(inout) :: s
        integer, intent(inout) :: st
        logical, intent(in), optional :: extrapolated
        character(len=*), intent(inout), optional :: msg
        if (st /= FSYM_SUCCESS .or. .not. present(extrapolated)) return
        if (extrapolated) call prime_in_place(s, st, msg)
    end subroutine prime_if

    !> Replace `s` by its extrapolated form (`s` unchanged on failure).
    subroutine prime_in_place(s, st, msg)
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        character(len=*), intent(inout), optional :: msg
        type(scheme_t) :: e
        call fsym_scheme_extrapolate(s, e, st, msg)
        if (st == FSYM_SUCCESS) call fsym_scheme_take(e, s)
    end subroutine prime_in_place

    !> `FSYM_LABEL_LEN` as text.
    pure function label_len_text() result(t)
        character(len=12) :: t
        write (t, '(i0)') FSYM_LABEL_LEN
    end function label_len_text

    !> `FSYM_AN_MAX` as text.
    pure function an_max_text() result(t)
        character(len=12) :: t
        write (t, '(i0)') FSYM_AN_MAX
    end function an_max_text

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
        character(len=shown_len) :: label
        call family_label('M1', t1, label, name)
        call mclachlan_family(t1, +1, OP_DRIFT, trim(label), scheme, stat, errmsg)
    end subroutine fsym_scheme_m1

    !> Non-forward family M2(t1) (paper eq. algm2, T and V exchanged, v2 of eq. v2m2), momentum
    !> first: kicks t2 t1 t0 t1 t2, drifts v2 v1 v1 v2.
    subroutine fsym_scheme_m2(t1, scheme, stat, errmsg, name)
        real(wp), intent(in) :: t1                      !! free parameter, < 0
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=*), intent(in), optional :: name  !! label (default `M2(t1)`)
        character(len=shown_len) :: label
        call family_label('M2', t1, label, name)
        call mclachlan_family(t1, -1, OP_KICK, trim(label), scheme, stat, errmsg)
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
        character(len=shown_len) :: label
        call fsym_gfr5_coefficients(alpha, a0, a1, a2, st, msg)
        if (st /= FSYM_SUCCESS) then
            call fsym_pass(st, msg, stat, errmsg); return
        end if
        call family_label('GFR5', alpha, label, name)
        call fsym_scheme_t2_product(trim(label), [a2, a1, a0, a1, a2], 4, scheme, stat, errmsg)
    end subroutine fsym_scheme_gfr5

    !> Blanes & Moan S6 in position-first form: 7 drifts, 6 kicks.
    function fsym_scheme_bm() result(s)
        type(scheme_t) :: s
        integer :: st
        call build_bm('BM', OP_DRIFT, s, st)
    end function fsym_scheme_bm

    !> Blanes & Moan S6 with the roles swapped (momentum first): 7 kicks, 6 drifts.
    function fsym_scheme_bm_mf() result(s)
        type(scheme_t) :: s
        integer :: st
        call build_bm('BM-mf', OP_KICK, s, st)
    end function fsym_scheme_bm_mf

    subroutine build_bm(label, first, s, st)
        character(len=*), intent(in) :: label
        integer, intent(in) :: first
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        real(wp) :: a4, b3
        a4 = 1.0_wp - 2.0_wp * (bm_a1 + bm_a2 + bm_a3)
        b3 = 0.5_wp - (bm_b1 + bm_b2)
        call alternating_custom(label, 4, first, mirror_odd([bm_a1, bm_a2, bm_a3, a4]), &
                                mirror_even([bm_b1, bm_b2, b3]), s, st)
    end subroutine build_bm

    !> Blanes & Moan RKN method SRKN6b (Table 3), momentum first: 7 kicks, 6 drifts.
    function fsym_scheme_srkn6b() result(s)
        type(scheme_t) :: s
        integer :: st
        call build_srkn6b(s, st)
    end function fsym_scheme_srkn6b

    subroutine build_srkn6b(s, st)
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        real(wp) :: b4, a3
        b4 = 1.0_wp - 2.0_wp * (srkn_b1 + srkn_b2 + srkn_b3)
        a3 = 0.5_wp - (srkn_a1 + srkn_a2)
        call alternating_custom('SRKN6b', 4, OP_KICK, &
                                mirror_odd([srkn_b1, srkn_b2, srkn_b3, b4]), &
                                mirror_even([srkn_a1, srkn_a2, a3]), s, st)
    end subroutine build_srkn6b

    !> `family(param)` unless the caller named the member (cut to the buffer).
    subroutine family_label(family, param, label, name)
        character(len=*), intent(in) :: family
        real(wp), intent(in) :: param
        character(len=*), intent(out) :: label
        character(len=*), intent(in), optional :: name
        character(len=32) :: buf
        if (present(name)) then
            label = name
        else
            write (buf, '(g0.6)') param
            call strip_zeros(buf)
            label = family//'('//trim(buf)//')'
        end if
    end subroutine family_label

    !> Drop trailing zeros of a decimal number in place: 0.500000 -> 0.5, -1.00000 -> -1.
    pure subroutine strip_zeros(s)
        character(len=*), intent(inout) :: s
        integer :: k
        s = adjustl(s)
        k = len_trim(s)
        if (index(s(1:k), '.') == 0 .or. scan(s(1:k), 'eE') > 0) return
        do while (k > 1 .and. s(k:k) == '0')
            k = k - 1
        end do
        if (s(k:k) == '.') k = k - 1
        s(k + 1:) = ''
    end subroutine strip_zeros

    !> The second-order kernels of the Wisdom-Holman splitting, in kick-drift-kick form (one
    !> Kepler drift per step; the force at the step's end is reused by the next step):
    !>
    !> * `WH`: kick 1/2, drift 1, kick 1/2 (the Wisdom-Holman map).
    !> * `WHK-M`, the modified-kick kernel: each half kick adds the gradient term,
    !>   v <- v + (h/2) a + (h^3/48) g with g = 2 (Da) a (the library's gradient), so that a
    !>   whole step kicks by h a + (h^3/12) (Da) a: the kick of J. Wisdom, M. Holman and
    !>   J. Touma, *Symplectic correctors*, Fields Inst. Commun. 10 (1996) 217, that removes
    !>   the eps^2 h^2 error term ([V,[T,V]]/12 of the drift-kick-drift leapfrog); the same
    !>   prefactor h^2/12 on (Da) a as in H. Rein, D. Tamayo and G. Brown, MNRAS 489 (2019)
    !>   4632 (WHCKM).
    !> * `WHK-L`, the lazy implementer's kernel: the same term by extrapolation (the paper's
    !>   A' idea), v <- v + (h/2) a(q + (h^2/12) a(q)): two forces per step, no gradient
    !>   (Wisdom, Holman & Touma 1996; WHCKL of Rein, Tamayo & Brown 2019). `WHK-M'` is it.
    !>
    !> Kick-drift-kick is conjugate to the drift-kick-drift kernels of those papers by
    !> S = (half kick) o (half drift): the correctors of `fsym_processed` include S.
    !>
    !> And the two-force methods of J. Laskar and P. Robutel, *High order symplectic
    !> integrators for perturbed Hamiltonian systems*, Celest. Mech. Dyn. Astron. 80 (2001)
    !> 39-62, whose error is eps h^4 + eps^2 h^2 (second order for T + V in general):
    !>
    !> * `SABA2`: drift c1, kick 1/2, drift c2, kick 1/2, drift c1 with c1 = 1/2 - sqrt(3)/6,
    !>   c2 = sqrt(3)/3;
    !> * `SBAB2`: kick 1/6, drift 1/2, kick 2/3, drift 1/2, kick 1/6 (the paper's A without
    !>   its gradient term; two forces per step, the last reused by the next step).
    subroutine build_wh_kernel(key, s, st)
        character(len=*), intent(in) :: key
        type(scheme_t), intent(inout) :: s
        integer, intent(out) :: st
        character(len=256) :: msg
        msg = ''
        select case (key)
        case ('whk-m')
            call fsym_scheme_custom('WHK-M', [OP_GRAD_KICK, OP_DRIFT, OP_GRAD_KICK], &
                                    [0.5_wp, 1.0_wp, 0.5_wp], &
                                    [1.0_wp / 48.0_wp, 0.0_wp, 1.0_wp / 48.0_wp], 2, s, st, msg)
        case ('whk-l')
            call fsym_scheme_custom('WHK-L', [OP_EXTRAP_KICK, OP_DRIFT, OP_EXTRAP_KICK], &
                                    [0.5_wp, 1.0_wp, 0.5_wp], &
                                    [1.0_wp / 12.0_wp, 0.0_wp, 1.0_wp / 12.0_wp], 2, s, st, msg)
        case ('saba2')
            call alternating_custom('SABA2', 2, OP_DRIFT, &
                                    [0.5_wp - sqrt(3.0_wp) / 6.0_wp, sqrt(3.0_wp) / 3.0_wp, &
                                     0.5_wp - sqrt(3.0_wp) / 6.0_wp], [0.5_wp, 0.5_wp], &
                                    s, st, msg)
        case ('sbab2')
            call alternating_custom('SBAB2', 2, OP_KICK, &
                                    [1.0_wp / 6.0_wp, 2.0_wp / 3.0_wp, 1.0_wp / 6.0_wp], &
                                    [0.5_wp, 0.5_wp], s, st, msg)
        case default
            call alternating_custom('WH', 2, OP_KICK, [0.5_wp, 0.5_wp], [1.0_wp], s, st, msg)
        end select
    end subroutine build_wh_kernel

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
    !> (3 <= N <= `FSYM_AN_MAX`), M1 (McLachlan's member), M1(t1), M2(t1), GFR5(alpha), BM,
    !> BM-mf, SRKN6b, the Wisdom-Holman kernels WH, WHK-M, WHK-L and Laskar and Robutel's
    !> SABA2, SBAB2. A prime may be written ',
    !> the Unicode prime, or `prime`; a parameter as a decimal number or a fraction p/q. Blanks
    !> are ignored; the rest may be at most `FSYM_LABEL_LEN` characters. On error `scheme` is
    !> untouched and `stat` says why (`FSYM_ERR_UNKNOWN_METHOD`, `FSYM_ERR_BAD_PARAMETER`,
    !> `FSYM_ERR_NO_MEMORY`).
    subroutine fsym_scheme_by_name(name, scheme, stat, errmsg)
        character(len=*), intent(in) :: name            !! method label
        type(scheme_t), intent(inout) :: scheme         !! result, set only on success
        integer, intent(out), optional :: stat          !! status code
        character(len=*), intent(inout), optional :: errmsg  !! message on error
        character(len=FSYM_LABEL_LEN) :: key
        character(len=shown_len) :: shown, member
        logical :: prime, has_arg, fits
        real(wp) :: x
        integer :: n, nk, nb, ios, st, p
        type(scheme_t) :: s
        character(len=256) :: msg

        call show(name, shown)
        call normalize(name, key, nk, fits)
        if (.not. fits) then
            call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(shown)//'": longer than '// &
                             'any label (at most '//trim(label_len_text())// &
                             ' characters without blanks)', stat, errmsg)
            return
        end if
        prime = .false.
        if (nk > 0) prime = key(nk:nk) == ''''
        if (prime) nk = nk - 1
        p = index(key(1:nk), '(')
        has_arg = p > 0
        x = 0.0_wp
        nb = nk
        if (has_arg) then
            if (key(nk:nk) /= ')') then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(shown)//'": missing )', &
                                 stat, errmsg)
                return
            end if
            nb = p - 1
            call parse_real(key(p + 1:nk - 1), x, ios)
            if (ios /= 0) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(shown)// &
                                 '": cannot read the parameter "'//key(p + 1:nk - 1)// &
                                 '" (a finite decimal number or p/q)', stat, errmsg)
                return
            end if
        end if
        call display(name, prime, member)

        st = FSYM_SUCCESS
        msg = ''
        select case (key(1:nb))
        case ('t2'); call alternating_custom('T2', 2, OP_DRIFT, [0.5_wp, 0.5_wp], [1.0_wp], &
                                             s, st, msg)
        case ('fr'); call build_fr(s, st)
        case ('a'); call build_a(s, st)
        case ('c'); call build_c(s, st)
        case ('bm'); call build_bm('BM', OP_DRIFT, s, st)
        case ('bm-mf'); call build_bm('BM-mf', OP_KICK, s, st)
        case ('srkn6b'); call build_srkn6b(s, st)
        case ('wh', 'whk-m', 'whk-l', 'saba2', 'sbab2'); call build_wh_kernel(key(1:nb), s, st)
        case ('m1')
            if (has_arg) then
                call fsym_scheme_m1(x, s, st, msg, name=trim(member))
            else
                call fsym_scheme_m1((121.0_wp / 3924.0_wp) * (12.0_wp - sqrt(471.0_wp)), s, st, &
                                    msg, name='M1')
            end if
        case ('m2')
            if (.not. has_arg) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(shown)// &
                                 '": M2 needs its parameter, e.g. M2(-0.5)', stat, errmsg)
                return
            end if
            call fsym_scheme_m2(x, s, st, msg, name=trim(member))
        case ('gfr5')
            if (.not. has_arg) then
                call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(shown)// &
                                 '": GFR5 needs its parameter, e.g. GFR5(1)', stat, errmsg)
                return
            end if
            call fsym_scheme_gfr5(x, s, st, msg, name=trim(member))
        case default
            if (nb >= 2 .and. key(1:1) == 'a' .and. verify(key(2:nb), '0123456789') == 0 &
                .and. .not. has_arg) then
                call read_an(key(2:nb), n)
                if (n < 0) then
                    call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(shown)// &
                                     '": AN needs N >= 3 and N <= '//trim(an_max_text())// &
                                     ', got N = '//key(2:nb), stat, errmsg)
                    return
                end if
                call fsym_scheme_an(n, s, stat=st, errmsg=msg)
            else if (key(1:nk) == 'rkn') then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(shown)//'" is the '// &
                                 'Runge-Kutta-Nystrom comparator, not a splitting: get it '// &
                                 'with fsym_new_stepper(''RKN'', model, d, n, stepper, '// &
                                 'stat, errmsg) or as type(rkn_t)', stat, errmsg)
                return
            else
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(shown)// &
                                 '" (known: T2 FR A A'' C C'' AN AN'' M1 M1(t1) M2(t1)'// &
                                 ' GFR5(alpha) BM BM-mf SRKN6b WH WHK-M WHK-L SABA2 SBAB2;'// &
                                 ' RKN is not a splitting)', stat, errmsg)
                return
            end if
        end select
        if (st /= FSYM_SUCCESS) then
            if (len_trim(msg) == 0) msg = 'no memory for the stage table of "'//trim(shown)//'"'
            call fsym_pass(st, msg, stat, errmsg)
            return
        end if
        if (has_arg .and. .not. any(key(1:nb) == [character(len=4) :: 'm1', 'm2', 'gfr5'])) then
            call fsym_report(FSYM_ERR_BAD_PARAMETER, '"'//trim(shown)//'" takes no parameter', &
                             stat, errmsg)
            return
        end if
        if (prime) then
            if (.not. s%needs_gradient()) then
                call fsym_report(FSYM_ERR_UNKNOWN_METHOD, '"'//trim(shown)// &
                                 '": only methods with a gradient kick have a primed form', &
                                 stat, errmsg)
                return
            end if
            call prime_in_place(s, st, msg)
            if (st /= FSYM_SUCCESS) then
                call fsym_pass(st, msg, stat, errmsg); return
            end if
        end if
        call fsym_scheme_take(s, scheme)
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine fsym_scheme_by_name

    !> N of an `AN` label from its digits, or -1 when it is outside 3..`FSYM_AN_MAX` (any
    !> number of digits: no integer overflow).
    pure subroutine read_an(digits, n)
        character(len=*), intent(in) :: digits
        integer, intent(out) :: n
        integer :: k
        n = 0
        do k = 1, len(digits)
            n = 10 * n + (iachar(digits(k:k)) - iachar('0'))
            if (n > FSYM_AN_MAX) then
                n = -1; return
            end if
        end do
        if (n < 3) n = -1
    end subroutine read_an

    !> The label as shown in messages: its first `FSYM_LABEL_LEN` characters, `...` if cut.
    pure subroutine show(name, shown)
        character(len=*), intent(in) :: name
        character(len=shown_len), intent(out) :: shown
        integer :: m
        m = len_trim(name)
        if (m <= FSYM_LABEL_LEN) then
            shown = name(1:m)
        else
            shown = name(1:FSYM_LABEL_LEN)
            shown(FSYM_LABEL_LEN + 1:) = '...'
        end if
    end subroutine show

    !> The user's label with blanks removed and without its prime (cut to the buffer).
    pure subroutine display(name, prime, d)
        character(len=*), intent(in) :: name
        logical, intent(in) :: prime
        character(len=shown_len), intent(out) :: d
        integer :: k, m
        d = ''
        m = 0
        do k = 1, len_trim(name)
            if (name(k:k) == ' ') cycle
            if (m == shown_len) exit
            m = m + 1
            d(m:m) = name(k:k)
        end do
        if (prime) then
            k = scan(d, '''')
            if (k == 0) k = index(d, char(226))
            if (k > 0) d(k:) = ''
        end if
    end subroutine display

    !> Lower case, no blanks, Unicode prime (U+2032) and a final word `prime` mapped to ',
    !> into `key(1:nk)`; `fits` is false when that is longer than `FSYM_LABEL_LEN`.
    pure subroutine normalize(name, key, nk, fits)
        character(len=*), intent(in) :: name
        character(len=FSYM_LABEL_LEN), intent(out) :: key
        integer, intent(out) :: nk
        logical, intent(out) :: fits
        character(len=3), parameter :: uprime = char(226)//char(128)//char(178)
        character(len=1) :: ch
        integer :: k, m, p
        key = ''
        nk = 0
        fits = .false.
        m = len_trim(name)
        k = 0
        do while (k < m)
            k = k + 1
            ch = name(k:k)
            if (ch == ' ') cycle
            if (k + 2 <= m) then
                if (name(k:k + 2) == uprime) then
                    ch = ''''; k = k + 2
                end if
            end if
            if (ch >= 'A' .and. ch <= 'Z') ch = achar(iachar(ch) + 32)
            if (nk == FSYM_LABEL_LEN) return
            nk = nk + 1
            key(nk:nk) = ch
        end do
        fits = .true.
        p = index(key(1:nk), 'prime')
        if (p > 0 .and. p + 4 == nk) then
            key(p:nk) = ''''
            nk = p
        end if
    end subroutine normalize

    !> Read a finite decimal number or a fraction p/q (q /= 0).
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
            if (den <= 0.0_wp .and. den >= 0.0_wp) then   ! den == 0
                ios = 1; return
            end if
            x = num / den
        else
            read (text, *, iostat=ios) x
            if (ios /= 0) x = 0.0_wp
        end if
        if (ios == 0 .and. .not. (abs(x) <= huge(x))) then
            x = 0.0_wp; ios = 1
        end if
    end subroutine parse_real

end module fsym_paper_schemes
