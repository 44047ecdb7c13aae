!> Tests of the scheme tables: catalogue, coefficients from the paper, metadata, names.
module test_scheme
    use fsym
    use testing
    implicit none
    private
    public :: collect_scheme

contains

    function collect_scheme() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [ &
            new_test('scheme: every catalogue entry builds and is consistent', t_catalogue), &
            new_test('scheme: forward flags as in the paper', t_forward), &
            new_test('scheme: force/gradient counts per step as in the paper', t_counts), &
            new_test('scheme: FR, GFR5 coefficients (eqs. fr, gfr5, susumc)', t_gfr5), &
            new_test('scheme: M1/M2 coefficients (eqs. algm1, v2m1, v2m2)', t_m1), &
            new_test('scheme: AN coefficients and primed forms', t_an), &
            new_test('scheme: name variants (case, primes, fractions)', t_names), &
            new_test('scheme: user tables checked for consistency', t_custom)]
    end function collect_scheme

    subroutine get(name, s, err)
        character(len=*), intent(in) :: name
        type(scheme_t), intent(out) :: s
        character(len=:), allocatable, intent(inout) :: err
        integer :: st
        character(len=256) :: msg
        call fsym_scheme_by_name(name, s, st, msg)
        call check(err, st == 0, 'cannot build '//name//': '//trim(msg))
    end subroutine get

    subroutine t_catalogue(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(scheme_t) :: s
        integer :: k
        names = fsym_catalogue()
        call check(err, size(names) >= 26, 'catalogue too short')
        do k = 1, size(names)
            call get(trim(names(k)), s, err)
            if (allocated(err)) return
            call check_close(err, sum(s%c, mask=s%op == OP_DRIFT), 1.0_wp, 1.0e-13_wp, &
                             trim(names(k))//' drift sum')
            call check_close(err, sum(s%c, mask=s%op /= OP_DRIFT), 1.0_wp, 1.0e-13_wp, &
                             trim(names(k))//' kick sum')
            call check(err, s%symmetric, trim(names(k))//' should be symmetric')
            call check(err, s%order == merge(2, 4, names(k) == 'T2'), trim(names(k))//' order')
        end do
    end subroutine t_catalogue

    subroutine t_forward(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=12), parameter :: fwd(*) = [character(len=12) :: 'T2', 'A', 'A''', &
            'C', 'C''', 'A3', 'A4', 'A5', 'A6', 'A5''', 'A6''', 'A9', 'A9''']
        character(len=12), parameter :: nonfwd(*) = [character(len=12) :: 'FR', 'M1', &
            'M1(-1/24)', 'M2(-0.1)', 'M2(-2)', 'GFR5(0.3)', 'GFR5(1)', 'BM', 'BM-mf', 'SRKN6b']
        type(scheme_t) :: s
        integer :: k
        do k = 1, size(fwd)
            call get(trim(fwd(k)), s, err)
            call check(err, s%forward, trim(fwd(k))//' must be forward')
        end do
        do k = 1, size(nonfwd)
            call get(trim(nonfwd(k)), s, err)
            call check(err, .not. s%forward, trim(nonfwd(k))//' must not be forward')
        end do
    end subroutine t_forward

    subroutine t_counts(err)
        character(len=:), allocatable, intent(out) :: err
        ! (name, forces, gradients) per step from the paper's text and shared/METHODS.md
        character(len=12), parameter :: names(*) = [character(len=12) :: 'T2', 'FR', 'A', &
            'A''', 'C', 'C''', 'A3', 'A5', 'A6', 'A6''', 'M1', 'M1(-1/24)', 'M2(-0.5)', &
            'GFR5(0)', 'GFR5(0.5)', 'BM', 'BM-mf', 'SRKN6b']
        integer, parameter :: nf(*) = [1, 3, 2, 3, 3, 4, 2, 4, 5, 6, 4, 4, 4, 3, 5, 6, 6, 6]
        integer, parameter :: ng(*) = [0, 0, 1, 0, 1, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0]
        type(scheme_t) :: s
        character(len=64) :: buf
        integer :: k
        do k = 1, size(names)
            call get(trim(names(k)), s, err)
            write (buf, '(a,2(1x,i0))') trim(names(k))//' counts', s%nforce, s%ngrad
            call check(err, s%nforce == nf(k) .and. s%ngrad == ng(k), trim(buf))
        end do
    end subroutine t_counts

    subroutine t_gfr5(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: a0, a1, a2, b0, b1, b2
        type(scheme_t) :: fr, g0, g1
        integer :: st
        call fsym_gfr5_coefficients(0.0_wp, a0, a1, a2, st)
        call check_close(err, a1, 1.0_wp / (2.0_wp - 2.0_wp**(1.0_wp / 3.0_wp)), 1e-14_wp, 'FR a1')
        call check_close(err, a1, 1.35_wp, 0.005_wp, 'FR a1 ~ 1.35')
        call check_close(err, a0, -1.70_wp, 0.005_wp, 'FR a0 ~ -1.70')
        call fsym_gfr5_coefficients(1.0_wp, a0, a1, a2, st)
        call check_close(err, a1, 1.0_wp / (4.0_wp - 4.0_wp**(1.0_wp / 3.0_wp)), 1e-14_wp, &
                         'GFR5(1) a1 (eq. susumc)')
        call check_close(err, a0, &
                         -4.0_wp**(1.0_wp / 3.0_wp) / (4.0_wp - 4.0_wp**(1.0_wp / 3.0_wp)), &
                         1e-14_wp, 'GFR5(1) a0')
        call check_close(err, a2, a1, 1e-15_wp, 'GFR5(1) a2 = a1')
        do st = 0, 20
            call fsym_gfr5_coefficients(0.1_wp * st, a0, a1, a2)
            call check_close(err, a0 + 2 * a1 + 2 * a2, 1.0_wp, 1e-13_wp, 'GFR5 sum a = 1')
            call check_close(err, a0**3 + 2 * a1**3 + 2 * a2**3, 0.0_wp, 1e-12_wp, &
                             'GFR5 sum a^3 = 0')
        end do
        ! a0 is least negative at alpha = 1 (paper, Fig. acoef)
        call fsym_gfr5_coefficients(0.9_wp, a0, a1, a2)
        call fsym_gfr5_coefficients(1.0_wp, b0, b1, b2)
        call check(err, b0 > a0, 'a0(1) should exceed a0(0.9)')
        call fsym_gfr5_coefficients(1.1_wp, a0, a1, a2)
        call check(err, b0 > a0, 'a0(1) should exceed a0(1.1)')
        fr = fsym_scheme_fr()
        call get('GFR5(0)', g0, err)
        call check(err, g0%nop == fr%nop, 'GFR5(0) must reduce to FR')
        if (g0%nop == fr%nop) call check(err, all(abs(g0%c - fr%c) < 1e-15_wp), 'GFR5(0) /= FR')
        call get('GFR5(1)', g1, err)
        call check(err, g1%nforce == 5, 'GFR5(1) has five forces')
    end subroutine t_gfr5

    subroutine t_m1(err)
        character(len=:), allocatable, intent(out) :: err
        real(wp) :: t0, t2, v1, v2, t1
        type(scheme_t) :: s
        t1 = (121.0_wp / 3924.0_wp) * (12.0_wp - sqrt(471.0_wp))
        call check_close(err, t1, -0.299_wp, 0.0005_wp, 'McLachlan t1 ~ -0.299')
        call fsym_m1_coefficients(-1.0_wp / 24.0_wp, +1, t0, t2, v1, v2)
        call check_close(err, v2, (1.0_wp + sqrt(5.0_wp)) / 4.0_wp, 1e-14_wp, 'M1(-1/24) v2')
        call check_close(err, t2, (11.0_wp - sqrt(5.0_wp)) / 48.0_wp, 1e-14_wp, 'M1(-1/24) t2')
        call get('M1', s, err)
        call check(err, s%name == 'M1', 'McLachlan member is called M1')
        call check_close(err, s%c(3), t1, 1e-15_wp, 'M1 default is McLachlan t1')
        call get('M2(-0.5)', s, err)
        call check(err, s%op(1) == OP_KICK .and. s%op(2) == OP_DRIFT, 'M2 is momentum first')
        call check_close(err, s%c(3), -0.5_wp, 1e-15_wp, 'M2(-0.5) carries t1 in a kick')
        call check(err, maxval(abs(s%c)) < 1.0_wp, 'M2 branch of eq. v2m2 has |v2| < 1')
    end subroutine t_m1

    subroutine t_an(err)
        character(len=:), allocatable, intent(out) :: err
        type(scheme_t) :: s, sp
        integer :: n, k
        do n = 3, 9
            call fsym_scheme_an(n, s)
            call check(err, count(s%op == OP_DRIFT) == n - 1, 'AN has N-1 drifts')
            call check(err, count(s%op == OP_KICK) == n - 2, 'AN has N-2 interior kicks')
            call check(err, s%op(1) == OP_GRAD_KICK .and. s%op(s%nop) == OP_GRAD_KICK, &
                       'AN ends are gradient kicks')
            call check_close(err, s%c(1), 1.0_wp / (2 * n), 1e-15_wp, 'AN end kick 1/(2N)')
            call check_close(err, s%u(1) / s%c(1), 1.0_wp / (24.0_wp * (n - 2)), 1e-15_wp, &
                             'AN gradient eps^2/(24(N-2))')
            do k = 1, s%nop
                if (s%op(k) == OP_DRIFT) call check_close(err, s%c(k), 1.0_wp / (n - 1), &
                                                          1e-15_wp, 'AN drift')
                if (s%op(k) == OP_KICK) call check_close(err, s%c(k), &
                                                         real(n - 1, wp) / (n * (n - 2)), &
                                                         1e-15_wp, 'AN kick')
            end do
            sp = s%extrapolated()
            call check(err, sp%op(1) == OP_EXTRAP_KICK, 'AN'' end kicks extrapolated')
            call check_close(err, sp%u(1), 1.0_wp / (12.0_wp * (n - 2)), 1e-15_wp, &
                             'AN'' shift eps^2/(12(N-2))')
            call check(err, .not. sp%symplectic .and. s%symplectic, &
                       'AN symplectic, AN'' not exactly')
        end do
        sp = fsym_scheme_a(extrapolated=.true.)
        call check_close(err, sp%u(3), 1.0_wp / 24.0_wp, 1e-15_wp, 'A'' shift 1/24 (eq. modfaex)')
        call check(err, sp%name == 'A''', 'A'' name')
        sp = fsym_scheme_c(extrapolated=.true.)
        call check_close(err, sp%u(4), 1.0_wp / 24.0_wp, 1e-15_wp, 'C'' shift 1/24')
    end subroutine t_an

    subroutine t_names(err)
        character(len=:), allocatable, intent(out) :: err
        type(scheme_t) :: s1, s2
        call get('a''', s1, err)
        call get('A'//char(226)//char(128)//char(178), s2, err)
        call check(err, s1%name == 'A''' .and. s2%name == 'A''', 'prime spellings')
        call get('Aprime', s2, err)
        call check(err, s2%name == 'A''', 'Aprime')
        call get('m2(-1/2)', s1, err)
        call get('M2(-0.5)', s2, err)
        call check(err, all(s1%c == s2%c), 'fraction parameter')
        call get(' bm-MF ', s1, err)
        call check(err, s1%name == 'BM-mf', 'case and blanks')
        call get('a6''', s1, err)
        call check(err, s1%name == 'A6''' .and. s1%nforce == 6, 'A6'' name and count')
    end subroutine t_names

    subroutine t_custom(err)
        character(len=:), allocatable, intent(out) :: err
        type(scheme_t) :: s
        integer :: st
        character(len=200) :: msg
        call fsym_scheme_custom('leapfrog', [OP_DRIFT, OP_KICK, OP_DRIFT], &
                                [0.5_wp, 1.0_wp, 0.5_wp], &
                                [0.0_wp, 0.0_wp, 0.0_wp], 2, s, st, msg)
        call check(err, st == 0 .and. s%nforce == 1 .and. s%forward, 'custom leapfrog')
        msg = ''
        call fsym_scheme_custom('bad', [OP_DRIFT, OP_KICK, OP_DRIFT], [0.5_wp, 0.9_wp, 0.5_wp], &
                                [0.0_wp, 0.0_wp, 0.0_wp], 2, s, st, msg)
        call check(err, st == FSYM_ERR_INCONSISTENT_SCHEME, 'kick sum 0.9 rejected')
        call check(err, index(msg, 'kicks') > 0, 'message names the kicks: '//trim(msg))
        call check(err, s%name == 'leapfrog', 'scheme untouched on error')
        call fsym_scheme_custom('bad', [OP_DRIFT, 7, OP_DRIFT], [0.5_wp, 1.0_wp, 0.5_wp], &
                                [0.0_wp, 0.0_wp, 0.0_wp], 2, s, st, msg)
        call check(err, st == FSYM_ERR_INCONSISTENT_SCHEME, 'op code 7 rejected')
    end subroutine t_custom

end module test_scheme
