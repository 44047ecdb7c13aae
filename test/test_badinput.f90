!> Bad input, nothing lost: a randomized test (fixed seed, a few hundred cases) feeding every
!> method non-finite states and steps, zero and huge steps, r = 0, model failures mid-step,
!> bad names and parameters and mismatched shapes. After every call: never stat = 0 with a
!> non-finite result; on failure a message, the caller's state unchanged bit for bit and the
!> step count unchanged; and the stepper still gives the same next step as a fresh one.
module test_badinput
    use, intrinsic :: iso_fortran_env, only: int64
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
                                             ieee_negative_inf
    use fsym
    use fsym_legacy_api, only: FSYMWK, FSYMIN, FSYMST, FSYMMS
    use testing
    implicit none
    private
    public :: collect_badinput

    integer, parameter :: ncases = 400

    !> Oscillator (a = -q, g = 2q) that fails on call number `fail_at` of acceleration or
    !> gradient, either through its status or by returning NaN.
    type, extends(force_model_t) :: faulty_model_t
        integer :: calls = 0
        integer :: fail_at = 0
        logical :: with_nan = .false.
    contains
        procedure :: acceleration => faulty_acc
        procedure :: gradient => faulty_grad
        procedure :: has_gradient => faulty_has
    end type faulty_model_t

    !> Small reproducible generator (64-bit LCG, Knuth's MMIX constants).
    type :: rng_t
        integer(int64) :: s = 20261122_int64
    end type rng_t

contains

    function collect_badinput() result(tests)
        type(test_t), allocatable :: tests(:)
        tests = [new_test('badinput: randomized bad inputs lose nothing', t_random), &
                 new_test('badinput: bad names and parameters leave the stepper', t_params), &
                 new_test('badinput: short or foreign work arrays (F77 layer)', t_legacy)]
    end function collect_badinput

    subroutine faulty_acc(self, q, a, stat)
        class(faulty_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(out), contiguous :: a(:, :)
        integer, intent(inout) :: stat
        self%calls = self%calls + 1
        a = -q
        if (self%calls == self%fail_at) call fail(self, a, stat)
    end subroutine faulty_acc

    subroutine faulty_grad(self, q, a, g, stat)
        class(faulty_model_t), intent(inout) :: self
        real(wp), intent(in), contiguous :: q(:, :)
        real(wp), intent(in), contiguous :: a(:, :)
        real(wp), intent(out), contiguous :: g(:, :)
        integer, intent(inout) :: stat
        self%calls = self%calls + 1
        g = 2.0_wp * q
        if (self%calls == self%fail_at) call fail(self, g, stat)
    end subroutine faulty_grad

    subroutine fail(self, x, stat)
        class(faulty_model_t), intent(in) :: self
        real(wp), intent(inout) :: x(:, :)
        integer, intent(inout) :: stat
        if (self%with_nan) then
            x(1, 1) = ieee_value(1.0_wp, ieee_quiet_nan)
        else
            stat = 7
        end if
    end subroutine fail

    logical function faulty_has(self)
        class(faulty_model_t), intent(in) :: self
        faulty_has = .true.
    end function faulty_has

    !> Uniform integer in [lo, hi].
    integer function irand(r, lo, hi)
        type(rng_t), intent(inout) :: r
        integer, intent(in) :: lo, hi
        r%s = r%s * 6364136223846793005_int64 + 1442695040888963407_int64
        irand = lo + int(modulo(ishft(r%s, -33), int(hi - lo + 1, int64)))
    end function irand

    !> Uniform real in [0, 1).
    real(wp) function urand(r)
        type(rng_t), intent(inout) :: r
        urand = real(irand(r, 0, 2**30 - 1), wp) / 2.0_wp**30
    end function urand

    !> Bitwise equality (NaN payloads included).
    logical function same_bits(a, b)
        real(wp), intent(in) :: a(:, :), b(:, :)
        same_bits = all(transfer(a, 1_int64, size(a)) == transfer(b, 1_int64, size(b)))
    end function same_bits

    logical function finite(a)
        real(wp), intent(in) :: a(:, :)
        finite = all(abs(a) <= huge(1.0_wp))
    end function finite

    real(wp) function bad_real(r)
        type(rng_t), intent(inout) :: r
        select case (irand(r, 1, 3))
        case (1); bad_real = ieee_value(1.0_wp, ieee_quiet_nan)
        case (2); bad_real = ieee_value(1.0_wp, ieee_positive_inf)
        case default; bad_real = ieee_value(1.0_wp, ieee_negative_inf)
        end select
    end function bad_real

    subroutine t_random(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        type(rng_t) :: r
        type(kepler_model_t) :: kep
        type(faulty_model_t) :: faulty
        class(stepper_t), allocatable :: s, fresh
        real(wp), allocatable :: q(:, :), v(:, :), q0(:, :), v0(:, :), qb(:, :), vb(:, :)
        real(wp) :: h
        integer :: icase, kind, d, n, st, k, j, nfail, nok
        integer(int64) :: nsteps0
        logical :: use_kepler
        character(len=256) :: msg
        character(len=160) :: where
        names = fsym_method_names()
        nfail = 0; nok = 0
        do icase = 1, ncases
            if (allocated(err)) exit
            kind = irand(r, 1, 8)
            d = irand(r, 1, 3); n = irand(r, 1, 3)
            use_kepler = kind == 4 .or. irand(r, 0, 1) == 0
            k = irand(r, 1, size(names))
            write (where, '(a,i0,a,i0,a,a,a,i0,a,i0)') 'case ', icase, ' kind ', kind, &
                ' method ', trim(names(k)), ' d ', d, ' n ', n
            faulty%calls = 0; faulty%fail_at = 0
            if (use_kepler) then
                call fsym_new_stepper(names(k), kep, d, n, s, st, msg)
            else
                call fsym_new_stepper(names(k), faulty, d, n, s, st, msg)
            end if
            call check(err, st == 0, trim(where)//': set-up failed: '//trim(msg))
            if (st /= 0) exit
            if (allocated(q)) deallocate (q, v, q0, v0, qb, vb)
            allocate (q(d, n), v(d, n), q0(d, n), v0(d, n), qb(d, n), vb(d, n))
            do j = 1, n
                q(:, j) = [(0.5_wp + urand(r), k = 1, d)]
                v(:, j) = [(urand(r) - 0.5_wp, k = 1, d)]
            end do
            k = irand(r, 1, size(names))
            ! a few good steps first, so that caches are warm
            do j = 1, irand(r, 0, 3)
                if (use_kepler) then
                    call s%step(kep, q, v, 1.0e-3_wp, st, msg)
                else
                    call s%step(faulty, q, v, 1.0e-3_wp, st, msg)
                end if
            end do
            qb = q; vb = v
            h = 1.0e-2_wp
            select case (kind)
            case (1)     ! non-finite state
                if (irand(r, 0, 1) == 0) then
                    q(irand(r, 1, d), irand(r, 1, n)) = bad_real(r)
                else
                    v(irand(r, 1, d), irand(r, 1, n)) = bad_real(r)
                end if
            case (2)     ! non-finite step
                h = bad_real(r)
            case (3)     ! zero step
                h = merge(0.0_wp, -0.0_wp, irand(r, 0, 1) == 0)
            case (4)     ! r = 0 in one column (Kepler)
                q(:, irand(r, 1, n)) = 0.0_wp
            case (5)     ! huge (or tiny) steps
                h = sign(10.0_wp**irand(r, 2, 300), urand(r) - 0.5_wp)
                if (irand(r, 0, 4) == 0) h = 1.0e-310_wp
            case (6)     ! model failure mid-step
                if (use_kepler) then
                    q(:, 1) = 0.0_wp
                else
                    faulty%fail_at = faulty%calls + irand(r, 1, 4)
                    faulty%with_nan = irand(r, 0, 1) == 0
                end if
            case default ! shape mismatches
                call wrong_shape(s, r, q, where, err)
                cycle
            end select
            q0 = q; v0 = v
            nsteps0 = s%steps()
            msg = ''
            if (use_kepler) then
                call s%step(kep, q, v, h, st, msg)
            else
                call s%step(faulty, q, v, h, st, msg)
            end if
            if (st == 0) then
                nok = nok + 1
                call check(err, finite(q) .and. finite(v), trim(where)//': stat = 0, non-finite')
                call check(err, s%steps() == nsteps0 + 1, trim(where)//': step not counted')
            else
                nfail = nfail + 1
                call check(err, len_trim(msg) > 0, trim(where)//': no message')
                call check(err, same_bits(q, q0) .and. same_bits(v, v0), &
                           trim(where)//': state changed on failure: '//trim(msg))
                call check(err, s%steps() == nsteps0, trim(where)//': failed step counted')
            end if
            ! usable afterwards: the next good step equals a fresh stepper's
            faulty%fail_at = 0
            q = qb; v = vb
            q0 = qb; v0 = vb
            if (use_kepler) then
                call fsym_new_stepper(s%name(), kep, d, n, fresh, st, msg)
                call s%step(kep, q, v, 1.0e-3_wp, st, msg)
                call fresh%step(kep, q0, v0, 1.0e-3_wp, k, msg)
            else
                call fsym_new_stepper(s%name(), faulty, d, n, fresh, st, msg)
                call s%step(faulty, q, v, 1.0e-3_wp, st, msg)
                call fresh%step(faulty, q0, v0, 1.0e-3_wp, k, msg)
            end if
            call check(err, st == 0 .and. k == 0 .and. same_bits(q, q0) .and. same_bits(v, v0), &
                       trim(where)//': not usable afterwards')
        end do
        write (msg, '(i0,a,i0,a,i0,a)') ncases, ' cases: ', nfail, ' refused, ', nok, &
            ' accepted with a finite result (plus shape cases)'
        call note(trim(msg))
        call check(err, nfail > ncases / 4, 'too few failures exercised')
    end subroutine t_random

    !> Arrays of the wrong shape: refused, untouched, message.
    subroutine wrong_shape(s, r, q, where, err)
        class(stepper_t), intent(inout) :: s
        type(rng_t), intent(inout) :: r
        real(wp), intent(in) :: q(:, :)
        character(len=*), intent(in) :: where
        character(len=:), allocatable, intent(inout) :: err
        type(kepler_model_t) :: kep
        real(wp), allocatable :: qq(:, :), vv(:, :), qc(:, :), vc(:, :)
        integer :: dd, nn, st
        character(len=256) :: msg
        dd = size(q, 1); nn = size(q, 2)
        select case (irand(r, 1, 3))
        case (1); allocate (qq(dd + 1, nn), vv(dd + 1, nn))
        case (2); allocate (qq(dd, nn + 1), vv(dd, nn + 1))
        case default; allocate (qq(dd, nn), vv(dd, nn + 1))
        end select
        qq = 0.75_wp; vv = 0.25_wp
        qc = qq; vc = vv
        msg = ''
        call s%step(kep, qq, vv, 1.0e-2_wp, st, msg)
        call check(err, st == FSYM_ERR_SHAPE .and. len_trim(msg) > 0, trim(where)// &
                   ': shape mismatch accepted')
        call check(err, same_bits(qq, qc) .and. same_bits(vv, vc), trim(where)// &
                   ': state changed by a shape mismatch')
    end subroutine wrong_shape

    !> Bad labels and dimensions: refused with a message, the caller's stepper kept.
    subroutine t_params(err)
        character(len=:), allocatable, intent(out) :: err
        character(len=12), parameter :: bad(*) = [character(len=12) :: 'A1', 'A2', 'XYZ', &
            'M2(abc)', 'GFR5(-1)', 'M2()', 'M1(xx)', '', 'T2 T2', 'A''''', 'AN(2)', 'RKN4', &
            'M2(1/0)', 'GFR5(nan)', 'M2(1e999)']
        type(rng_t) :: r
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1)
        integer :: k, st, d, n
        character(len=256) :: msg
        call fsym_new_stepper('C', kep, 2, 1, s, st, msg)
        do k = 1, 60
            msg = ''
            if (k <= size(bad)) then
                call fsym_new_stepper(bad(k), kep, 2, 1, s, st, msg)
            else
                d = irand(r, -2, 0); n = irand(r, -2, 2)
                if (irand(r, 0, 1) == 0) then
                    call fsym_new_stepper('FR', kep, d, n, s, st, msg)
                else
                    call fsym_new_stepper('RKN', kep, n, d, s, st, msg)
                end if
            end if
            call check(err, st /= 0 .and. len_trim(msg) > 0, 'bad parameter accepted, case '// &
                       trim(bad(min(k, size(bad)))))
            call check(err, s%name() == 'C', 'stepper replaced by a failed construction')
        end do
        q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
        call s%step(kep, q, v, 0.01_wp, st, msg)
        call check(err, st == 0 .and. finite(q), 'stepper not usable after bad parameters')
    end subroutine t_params

    !> F77 oscillator a = -x.
    subroutine f77_accel(nd, n, x, a)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n)
        real(wp), intent(out) :: a(nd, n)
        a = -x
    end subroutine f77_accel

    !> F77 gradient term g = 2x.
    subroutine f77_grad(nd, n, x, a, g)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n), a(nd, n)
        real(wp), intent(out) :: g(nd, n)
        g = 2.0_wp * x + 0.0_wp * a
    end subroutine f77_grad

    !> The F77 layer with work arrays that are too short, set up for other dimensions, or a
    !> non-finite state: INFO /= 0 with a message, the arrays and the state untouched; the
    !> same arrays then work when used correctly.
    subroutine t_legacy(err)
        character(len=:), allocatable, intent(out) :: err
        type(rng_t) :: r
        real(wp), allocatable :: rw(:), rw0(:)
        integer, allocatable :: iw(:), iw0(:)
        real(wp), allocatable :: x(:, :), v(:, :), x0(:, :), v0(:, :)
        integer :: icase, meth, nd, n, lrw, liw, info, k, kind
        character(len=128) :: msg, where
        r%s = 77_int64
        do icase = 1, 200
            if (allocated(err)) exit
            meth = irand(r, 1, size(fsym_catalogue()))
            nd = irand(r, 1, 3); n = irand(r, 1, 3)
            write (where, '(a,i0,a,i0)') 'legacy case ', icase, ' method ', meth
            call FSYMWK(meth, nd, n, lrw, liw, info)
            call check(err, info == 0 .and. lrw > 0 .and. liw > 0, trim(where)//': FSYMWK')
            if (info /= 0) exit
            if (allocated(rw)) deallocate (rw, iw, x, v)
            allocate (rw(lrw), iw(liw), x(nd, n), v(nd, n))
            rw = 7.0_wp; iw = 7
            x = 0.5_wp; v = 0.25_wp
            kind = irand(r, 1, 4)
            if (kind == 1) then
                ! too short for FSYMIN: rejected, nothing written
                k = irand(r, 0, 1)
                rw0 = rw; iw0 = iw
                call FSYMIN(meth, nd, n, rw, lrw - 1 + k, iw, liw - k, info)
                call FSYMMS(info, msg)
                call check(err, info == FSYM_ERR_WORK_SIZE .and. len_trim(msg) > 0, &
                           trim(where)//': short array accepted by FSYMIN')
                call check(err, all(rw == rw0) .and. all(iw == iw0), &
                           trim(where)//': FSYMIN wrote into a short array')
            end if
            call FSYMIN(meth, nd, n, rw, lrw, iw, liw, info)
            call check(err, info == 0, trim(where)//': FSYMIN')
            x0 = x; v0 = v
            select case (kind)
            case (2)     ! the set-up arrays passed with shorter lengths
                k = irand(r, 0, 1)
                call FSYMST(nd, n, x, v, 0.01_wp, 1, f77_accel, f77_grad, rw, lrw - 1 + k, iw, &
                            max(8, liw - k), info)
            case (3)     ! arrays set up for other dimensions
                call FSYMST(nd, n + 1, x, v, 0.01_wp, 1, f77_accel, f77_grad, rw, lrw, iw, &
                            liw, info)
            case (4)     ! non-finite state
                x(irand(r, 1, nd), irand(r, 1, n)) = bad_real(r)
                x0 = x
                call FSYMST(nd, n, x, v, 0.01_wp, 1, f77_accel, f77_grad, rw, lrw, iw, liw, info)
            case default ! a bad step
                call FSYMST(nd, n, x, v, bad_real(r), 1, f77_accel, f77_grad, rw, lrw, iw, &
                            liw, info)
            end select
            call FSYMMS(info, msg)
            call check(err, info /= 0 .and. len_trim(msg) > 0, trim(where)//': accepted')
            call check(err, same_bits(x, x0) .and. same_bits(v, v0), &
                       trim(where)//': state changed on failure')
            x = 0.5_wp; v = 0.25_wp
            call FSYMST(nd, n, x, v, 0.01_wp, 3, f77_accel, f77_grad, rw, lrw, iw, liw, info)
            call check(err, info == 0 .and. finite(x) .and. finite(v), &
                       trim(where)//': not usable afterwards')
        end do
    end subroutine t_legacy

end module test_badinput
