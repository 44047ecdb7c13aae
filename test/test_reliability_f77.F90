!> Defects of the F77 and reverse-communication faces (issue 11, items 2, 4, 5, 6, 8, 9, 11):
!> each test here failed before its fix. Planar Kepler bodies about a centre of mass `gm`
!> (a module variable, so that a test can change it between steps as a user changes a mass).
module test_reliability_f77
    use, intrinsic :: iso_fortran_env, only: int32, int64
    use funit
    use fsym
    use fsym_legacy_api
    implicit none

    real(wp) :: gm = 1.0_wp     !! the centre's G M, read by the routines below

contains

    !@before
    subroutine reset_mass()
        gm = 1.0_wp
    end subroutine reset_mass

    subroutine accel(nd, n, x, a)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n)
        real(wp), intent(out) :: a(nd, n)
        call kepler_field(nd, n, gm, x, a)
    end subroutine accel

    subroutine grad(nd, n, x, a, g)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n), a(nd, n)
        real(wp), intent(out) :: g(nd, n)
        call kepler_field_gradient(nd, n, gm, x, a, g)
    end subroutine grad

    !> A "gradient" routine that does nothing (what a user without a gradient writes).
    subroutine nograd(nd, n, x, a, g)
        integer, intent(in) :: nd, n
        real(wp), intent(in) :: x(nd, n), a(nd, n)
        real(wp), intent(out) :: g(nd, n)
        g = 0.0_wp
    end subroutine nograd

    !> Work arrays set up for `label` on (2, 1); the paper's orbit in x, v.
    subroutine setup(label, rw, iw, x, v)
        character(len=*), intent(in) :: label
        real(wp), allocatable, intent(out) :: rw(:)
        integer, allocatable, intent(out) :: iw(:)
        real(wp), intent(out) :: x(2, 1), v(2, 1)
        integer :: lrw, liw, info
        call FSYMWL(label, 2, 1, lrw, liw, info)
#line 50 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, 'FSYMWL '//label, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/wt11/test/test_reliability_f77.pf"
        allocate (rw(lrw), iw(liw))
        call FSYMIL(label, 2, 1, rw, lrw, iw, liw, info)
#line 53 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, 'FSYMIL '//label, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 53) )
  if (anyExceptions()) return
#line 54 "/work/wt11/test/test_reliability_f77.pf"
        call kepler_paper_orbit(x(:, 1), v(:, 1))
    end subroutine setup

    !> One reverse-communication step of h, answering every request with the routines above.
    subroutine rc_step(x, v, h, rw, iw, info)
        real(wp), intent(inout) :: x(2, 1), v(2, 1)
        real(wp), intent(in) :: h
        real(wp), intent(inout) :: rw(:)
        integer, intent(inout) :: iw(:)
        integer, intent(out) :: info
        integer :: ireq, ipnt(3), k
        ireq = 0
        do k = 1, 100
            call FSYMRC(2, 1, x, v, h, rw, size(rw), iw, size(iw), ireq, ipnt, info)
            select case (ireq)
            case (1)
                call accel(2, 1, x, rw(ipnt(2):ipnt(2) + 1))
            case (2)
                call grad(2, 1, x, rw(ipnt(3):ipnt(3) + 1), rw(ipnt(2):ipnt(2) + 1))
            case (3)
                call accel(2, 1, rw(ipnt(1):ipnt(1) + 1), rw(ipnt(2):ipnt(2) + 1))
            case default
                return
            end select
        end do
    end subroutine rc_step

    !> Item 2: work sizes beyond a default integer are an error, not a wrapped number; FSYMIN
    !> then refuses a small array.
    !@test
    subroutine test_work_size_overflow()
        integer :: lrw, liw, info, meth, iw(40)
        real(wp) :: rw(200)
        call FSYMID('FR', meth)
        call FSYMWK(meth, 3, 200000000, lrw, liw, info)
#line 89 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, 'FSYMWK N = 2e8', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/wt11/test/test_reliability_f77.pf"
#line 90 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, lrw, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 90) )
  if (anyExceptions()) return
#line 91 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMIN(meth, 3, 200000000, rw, size(rw), iw, size(iw), info)
#line 92 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, 'FSYMIN N = 2e8 with 200 reals', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 92) )
  if (anyExceptions()) return
#line 93 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMWK(meth, 3, 1000, lrw, liw, info)
#line 94 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 94) )
  if (anyExceptions()) return
#line 95 "/work/wt11/test/test_reliability_f77.pf"
#line 95 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(lrw > 3000, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 95) )
  if (anyExceptions()) return
#line 96 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_work_size_overflow

    !> Item 2: a work array set up for small N cannot be used for a huge N (the length check
    !> must not overflow either).
    !@test
    subroutine test_length_check_overflow()
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1)
        integer :: info
        call setup('FR', rw, iw, x, v)
        iw(3) = 1073741824    ! as if set up for N = 2**30: lengths overflow a default integer
        call FSYMST(2, 1073741824, x, v, 0.1_wp, 1, accel, grad, rw, size(rw), iw, size(iw), &
                    info)
#line 110 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 110) )
  if (anyExceptions()) return
#line 111 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_length_check_overflow

    !> Item 4: a wrong request code restores X, V; the next step starts afresh and works.
    !@test
    subroutine test_rc_wrong_request_restores()
        real(wp), allocatable :: rw(:), rw2(:)
        integer, allocatable :: iw(:), iw2(:)
        real(wp) :: x(2, 1), v(2, 1), x0(2, 1), v0(2, 1), x2(2, 1), v2(2, 1)
        integer :: ireq, ipnt(3), info, k
        call setup('C', rw, iw, x, v)
        call setup('C', rw2, iw2, x2, v2)
        x0 = x; v0 = v
        ! advance to a request in mid-step (after a drift)
        ireq = 0
        call FSYMRC(2, 1, x, v, 0.1_wp, rw, size(rw), iw, size(iw), ireq, ipnt, info)
        do k = 1, 3
            if (ireq /= 1) exit
            call accel(2, 1, x, rw(ipnt(2):ipnt(2) + 1))
            call FSYMRC(2, 1, x, v, 0.1_wp, rw, size(rw), iw, size(iw), ireq, ipnt, info)
        end do
#line 131 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(ireq > 0, 'a request is pending', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 131) )
  if (anyExceptions()) return
#line 132 "/work/wt11/test/test_reliability_f77.pf"
        ireq = 7          ! a code never issued
        call FSYMRC(2, 1, x, v, 0.1_wp, rw, size(rw), iw, size(iw), ireq, ipnt, info)
#line 134 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_BAD_REQUEST, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 134) )
  if (anyExceptions()) return
#line 135 "/work/wt11/test/test_reliability_f77.pf"
#line 135 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(-1, ireq, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 135) )
  if (anyExceptions()) return
#line 136 "/work/wt11/test/test_reliability_f77.pf"
#line 136 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(x == x0) .and. all(v == v0), 'X, V restored', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 136) )
  if (anyExceptions()) return
#line 137 "/work/wt11/test/test_reliability_f77.pf"
        ! the face is usable again: a full step equals one of a fresh work array
        call rc_step(x, v, 0.1_wp, rw, iw, info)
#line 139 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, 'next step', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 139) )
  if (anyExceptions()) return
#line 140 "/work/wt11/test/test_reliability_f77.pf"
        call rc_step(x2, v2, 0.1_wp, rw2, iw2, info)
#line 141 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(x == x2) .and. all(v == v2), 'bitwise as a fresh run', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 141) )
  if (anyExceptions()) return
#line 142 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_rc_wrong_request_restores

    !> Item 5: FSYMG0 says "no gradient term": A is refused with the state unchanged, A' runs;
    !> the no-op gradient a user would write instead gives a wrong method silently.
    !@test
    subroutine test_no_gradient_refused()
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1), x0(2, 1), v0(2, 1)
        integer :: info
        call setup('A', rw, iw, x, v)
        x0 = x; v0 = v
        call FSYMST(2, 1, x, v, 0.1_wp, 10, accel, FSYMG0, rw, size(rw), iw, size(iw), info)
#line 155 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_NO_GRADIENT, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 155) )
  if (anyExceptions()) return
#line 156 "/work/wt11/test/test_reliability_f77.pf"
#line 156 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(x == x0) .and. all(v == v0), 'state unchanged', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 156) )
  if (anyExceptions()) return
#line 157 "/work/wt11/test/test_reliability_f77.pf"
        call setup('A''', rw, iw, x, v)
        call FSYMST(2, 1, x, v, 0.1_wp, 10, accel, FSYMG0, rw, size(rw), iw, size(iw), info)
#line 159 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, 'A'' without gradient runs', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 159) )
  if (anyExceptions()) return
#line 160 "/work/wt11/test/test_reliability_f77.pf"
        ! the method without a gradient routine still refuses only gradient methods
        call setup('FR', rw, iw, x, v)
        call FSYMST(2, 1, x, v, 0.1_wp, 10, accel, FSYMG0, rw, size(rw), iw, size(iw), info)
#line 163 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, 'FR with FSYMG0', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 163) )
  if (anyExceptions()) return
#line 164 "/work/wt11/test/test_reliability_f77.pf"
        ! what the marker prevents: a no-op GRAD runs A silently with a wrong gradient
        call setup('A', rw, iw, x, v)
        call FSYMST(2, 1, x, v, 0.1_wp, 10, accel, nograd, rw, size(rw), iw, size(iw), info)
#line 167 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 167) )
  if (anyExceptions()) return
#line 168 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_no_gradient_refused

    !> Item 6: after a change of the centre's mass, FSYMRS makes FSYMST and FSYMRC use the new
    !> force from the first kick on: bitwise as a fresh start from the same state (method A,
    !> whose step starts with a kick that reuses the force of the previous step).
    !@test
    subroutine test_cache_reset_f77_rc()
        real(wp), allocatable :: rw(:), rwf(:)
        integer, allocatable :: iw(:), iwf(:)
        real(wp) :: x(2, 1), v(2, 1), xf(2, 1), vf(2, 1)
        integer :: info, face
        do face = 1, 2
            gm = 1.0_wp
            call setup('A', rw, iw, x, v)
            call advance(face, x, v, rw, iw)
            gm = 1.01_wp
            call FSYMRS(2, 1, x, v, rw, size(rw), iw, size(iw), info)
#line 185 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 185) )
  if (anyExceptions()) return
#line 186 "/work/wt11/test/test_reliability_f77.pf"
            call setup('A', rwf, iwf, xf, vf)
            xf = x; vf = v
            call advance(face, x, v, rw, iw)
            call advance(face, xf, vf, rwf, iwf)
#line 190 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(x == xf) .and. all(v == vf), 'reset = fresh start', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 190) )
  if (anyExceptions()) return
#line 191 "/work/wt11/test/test_reliability_f77.pf"
            ! and without the reset the first kick uses the stale force
            gm = 1.0_wp
            call setup('A', rw, iw, x, v)
            call advance(face, x, v, rw, iw)
            gm = 1.01_wp
            xf = x; vf = v
            call setup('A', rwf, iwf, xf, vf)
            xf = x; vf = v
            call advance(face, x, v, rw, iw)
            call advance(face, xf, vf, rwf, iwf)
#line 201 "/work/wt11/test/test_reliability_f77.pf"
  call assertFalse(all(v == vf), 'stale force without reset', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 201) )
  if (anyExceptions()) return
#line 202 "/work/wt11/test/test_reliability_f77.pf"
        end do
        gm = 1.0_wp
    contains
        subroutine advance(face, x, v, rw, iw)
            integer, intent(in) :: face
            real(wp), intent(inout) :: x(2, 1), v(2, 1), rw(:)
            integer, intent(inout) :: iw(:)
            integer :: info
            if (face == 1) then
                call FSYMST(2, 1, x, v, 0.1_wp, 1, accel, grad, rw, size(rw), iw, size(iw), info)
            else
                call rc_step(x, v, 0.1_wp, rw, iw, info)
            end if
#line 215 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 215) )
  if (anyExceptions()) return
#line 216 "/work/wt11/test/test_reliability_f77.pf"
        end subroutine advance
    end subroutine test_cache_reset_f77_rc

    !> Item 8: the codes say what is wrong: another shape 7, a short work array 10, never 9.
    !@test
    subroutine test_f77_codes()
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1), x3(3, 1), v3(3, 1)
        integer :: info, ireq, ipnt(3)
        call setup('FR', rw, iw, x, v)
        x3 = 1.0_wp; v3 = 0.0_wp
        call FSYMST(3, 1, x3, v3, 0.1_wp, 1, accel, grad, rw, size(rw), iw, size(iw), info)
#line 229 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_SHAPE, info, 'FSYMST shape', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 229) )
  if (anyExceptions()) return
#line 230 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMST(2, 1, x, v, 0.1_wp, 1, accel, grad, rw, size(rw) - 1, iw, size(iw), info)
#line 231 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, 'FSYMST short RW', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 231) )
  if (anyExceptions()) return
#line 232 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMST(2, 1, x, v, 0.1_wp, 1, accel, grad, rw, size(rw), iw, size(iw) - 1, info)
#line 233 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, 'FSYMST short IW', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 233) )
  if (anyExceptions()) return
#line 234 "/work/wt11/test/test_reliability_f77.pf"
        ireq = 0
        call FSYMRC(3, 1, x3, v3, 0.1_wp, rw, size(rw), iw, size(iw), ireq, ipnt, info)
#line 236 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_SHAPE, info, 'FSYMRC shape', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 236) )
  if (anyExceptions()) return
#line 237 "/work/wt11/test/test_reliability_f77.pf"
        ireq = 0
        call FSYMRC(2, 1, x, v, 0.1_wp, rw, size(rw) - 1, iw, size(iw), ireq, ipnt, info)
#line 239 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_WORK_SIZE, info, 'FSYMRC short RW', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 239) )
  if (anyExceptions()) return
#line 240 "/work/wt11/test/test_reliability_f77.pf"
        iw(1) = 0
        call FSYMST(2, 1, x, v, 0.1_wp, 1, accel, grad, rw, size(rw), iw, size(iw), info)
#line 242 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_NOT_INITIALIZED, info, 'not set up', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 242) )
  if (anyExceptions()) return
#line 243 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_f77_codes

    !> Item 8: FSYMID matches parametrised labels whatever their spelling; labels outside
    !> the catalogue are reachable by FSYMIL and give the modern API's numbers bit for bit.
    !@test
    subroutine test_f77_labels()
        integer :: m1, m2, m3, info, k
        character(len=8), parameter :: labels(2) = [character(len=8) :: 'A7', 'M2(-0.3)']
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1), q(2, 1), p(2, 1)
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        call FSYMID('M2(-0.5)', m1)
        call FSYMID('m2(-0.5)', m2)
        call FSYMID('M2(-1/2)', m3)
#line 259 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(m1 > 0, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 259) )
  if (anyExceptions()) return
#line 260 "/work/wt11/test/test_reliability_f77.pf"
#line 260 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(m1, m2, 'lower case', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 260) )
  if (anyExceptions()) return
#line 261 "/work/wt11/test/test_reliability_f77.pf"
#line 261 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(m1, m3, 'fraction', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 261) )
  if (anyExceptions()) return
#line 262 "/work/wt11/test/test_reliability_f77.pf"
        do k = 1, size(labels)
            call setup(trim(labels(k)), rw, iw, x, v)
            call FSYMST(2, 1, x, v, 0.05_wp, 20, accel, grad, rw, size(rw), iw, size(iw), info)
#line 265 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, info, trim(labels(k)), &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 265) )
  if (anyExceptions()) return
#line 266 "/work/wt11/test/test_reliability_f77.pf"
            call it%init_by_name(trim(labels(k)), kep, 2, 1, info)
            call kepler_paper_orbit(q(:, 1), p(:, 1))
            call it%run(kep, q, p, 0.05_wp, 20, info)
#line 269 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(x == q) .and. all(v == p), 'F77 = modern: '//trim(labels(k)), &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 269) )
  if (anyExceptions()) return
#line 270 "/work/wt11/test/test_reliability_f77.pf"
        end do
    end subroutine test_f77_labels

    !> Item 9: counts past 2**31 are not wrapped: FSYMNF says -1, FSYMNL gives them.
    !@test
    subroutine test_counts_64bit()
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1)
        integer :: nf, ng
        integer(int64) :: nf8, ng8
        call setup('A', rw, iw, x, v)
        rw(3) = 3.0e9_wp      ! the force count kept in RW(3), as after 3e9 evaluations
        rw(4) = 7.0_wp
        call FSYMNF(rw, size(rw), nf, ng)
#line 285 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(-1, nf, 'FSYMNF beyond 2**31', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 285) )
  if (anyExceptions()) return
#line 286 "/work/wt11/test/test_reliability_f77.pf"
#line 286 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(7, ng, &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 286) )
  if (anyExceptions()) return
#line 287 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMNL(rw, size(rw), nf8, ng8)
#line 288 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(nf8 == 3000000000_int64, 'FSYMNL', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 288) )
  if (anyExceptions()) return
#line 289 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_counts_64bit

    !> Item 11: the calling-convention check tells 4-byte from 8-byte caller integers.
    !@test
    subroutine test_calling_convention()
        integer(int32) :: i4(2)
        integer(int64) :: i8(2)
        i4 = [1, 2]
        call FSYMCV(i4, 1.5_wp)
#line 298 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(0, i4(1), '4-byte caller', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 298) )
  if (anyExceptions()) return
#line 299 "/work/wt11/test/test_reliability_f77.pf"
        i8 = [1_int64, 2_int64]
        call check8(i8)
#line 301 "/work/wt11/test/test_reliability_f77.pf"
  call assertTrue(all(i8 == FSYM_ERR_CONVENTION), '8-byte caller detected', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 301) )
  if (anyExceptions()) return
#line 302 "/work/wt11/test/test_reliability_f77.pf"
        i4 = [1, 2]
        call FSYMCV(i4, 1.25_wp)
#line 304 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_CONVENTION, i4(1), 'double precision mismatch', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 304) )
  if (anyExceptions()) return
#line 305 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_calling_convention

    !> What a code built with -fdefault-integer-8 passes: its INTEGER array, seen by the
    !> library as 4-byte words.
    subroutine check8(i8)
        use, intrinsic :: iso_c_binding, only: c_loc, c_f_pointer
        integer(int64), intent(inout), target :: i8(2)
        integer(int32), pointer :: words(:)
        call c_f_pointer(c_loc(i8), words, [4])
        call FSYMCV(words, 1.5_wp)
    end subroutine check8

    !> Item 13: a step count <= 0 is refused, not a silent success.
    !@test
    subroutine test_f77_nonpositive_count()
        real(wp), allocatable :: rw(:)
        integer, allocatable :: iw(:)
        real(wp) :: x(2, 1), v(2, 1)
        integer :: info
        call setup('FR', rw, iw, x, v)
        call FSYMST(2, 1, x, v, 0.1_wp, 0, accel, grad, rw, size(rw), iw, size(iw), info)
#line 326 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_BAD_ARGUMENT, info, 'NSTEP = 0', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 326) )
  if (anyExceptions()) return
#line 327 "/work/wt11/test/test_reliability_f77.pf"
        call FSYMST(2, 1, x, v, 0.1_wp, -5, accel, grad, rw, size(rw), iw, size(iw), info)
#line 328 "/work/wt11/test/test_reliability_f77.pf"
  call assertEqual(FSYM_ERR_BAD_ARGUMENT, info, 'NSTEP < 0', &
 & location=SourceLocation( &
 & 'test_reliability_f77.pf', &
 & 328) )
  if (anyExceptions()) return
#line 329 "/work/wt11/test/test_reliability_f77.pf"
    end subroutine test_f77_nonpositive_count

end module test_reliability_f77

module Wraptest_reliability_f77
   use FUnit
   use test_reliability_f77
   implicit none
   private

contains


end module Wraptest_reliability_f77

function test_reliability_f77_suite() result(suite)
   use FUnit
   use test_reliability_f77
   use Wraptest_reliability_f77
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_reliability_f77_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_work_size_overflow', &
      test_work_size_overflow, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_length_check_overflow', &
      test_length_check_overflow, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_rc_wrong_request_restores', &
      test_rc_wrong_request_restores, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_no_gradient_refused', &
      test_no_gradient_refused, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_cache_reset_f77_rc', &
      test_cache_reset_f77_rc, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_f77_codes', &
      test_f77_codes, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_f77_labels', &
      test_f77_labels, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_counts_64bit', &
      test_counts_64bit, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_calling_convention', &
      test_calling_convention, setUp=reset_mass))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_f77_nonpositive_count', &
      test_f77_nonpositive_count, setUp=reset_mass))
   call suite%addTest(t)


end function test_reliability_f77_suite

