!> Tests of the Kepler module against finite differences, conservation laws and the exact
!> solution.
module test_kepler
    use fsym
    use funit
    implicit none

contains

    !> kepler: acceleration = -grad V (finite differences, 2D and 3D)
    !@test
    subroutine test_force()
        real(wp) :: q(3), a(3), qp(3), qm(3), fd
        integer :: k, d
        real(wp), parameter :: hh = 1e-5_wp
        do d = 2, 3
            q(1:3) = [0.7_wp, -1.3_wp, 0.4_wp]
            call kepler_acceleration(q(1:d), a(1:d), mu=2.5_wp)
            do k = 1, d
                qp = q; qm = q
                qp(k) = q(k) + hh; qm(k) = q(k) - hh
                fd = -(kepler_potential(qp(1:d), 2.5_wp) - kepler_potential(qm(1:d), 2.5_wp)) &
                     / (2 * hh)
#line 24 "/work/wt12/test/test_kepler.pf"
  call assertEqual(fd, a(k), 1e-8_wp, 'a vs -dV/dq', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 24) )
  if (anyExceptions()) return
#line 25 "/work/wt12/test/test_kepler.pf"
            end do
        end do
    end subroutine test_force

    !> kepler: gradient term = grad |a|^2 (finite differences)
    !@test
    subroutine test_gradient()
        real(wp) :: q(3), g(3), qp(3), qm(3), ap(3), am(3), fd
        type(kepler_model_t) :: m
        real(wp) :: qq(3, 1), aa(3, 1), gg(3, 1)
        integer :: k, st
        real(wp), parameter :: hh = 1e-5_wp
        q = [0.9_wp, 0.2_wp, -0.5_wp]
        call kepler_gradient(q, g)
        do k = 1, 3
            qp = q; qm = q
            qp(k) = q(k) + hh; qm(k) = q(k) - hh
            call kepler_acceleration(qp, ap); call kepler_acceleration(qm, am)
            fd = (sum(ap**2) - sum(am**2)) / (2 * hh)
#line 44 "/work/wt12/test/test_kepler.pf"
  call assertEqual(fd, g(k), 1e-7_wp * max(1.0_wp, abs(fd)), 'g vs d|a|^2/dq', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 44) )
  if (anyExceptions()) return
#line 45 "/work/wt12/test/test_kepler.pf"
        end do
        qq(:, 1) = q; st = 0
        call m%acceleration(qq, aa, st)
        call m%gradient(qq, aa, gg, st)
#line 49 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs(gg(:, 1) - g)) < 1e-13_wp * maxval(abs(g)), 'model gradient', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/wt12/test/test_kepler.pf"
#line 50 "/work/wt12/test/test_kepler.pf"
  call assertEqual(-4.0_wp * q(1) / sum(q**2)**3, g(1), 1e-13_wp, '-4q/r^6', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/wt12/test/test_kepler.pf"
    end subroutine test_gradient

    !> kepler: paper orbit elements e = 0.9, E0 = -0.095, P
    !@test
    subroutine test_elements()
        real(wp) :: q(2), v(2), p, a, e, pp
        integer :: st
        call kepler_paper_orbit(q, v, p)
        call kepler_elements(q, v, a, e, pp, st)
#line 60 "/work/wt12/test/test_kepler.pf"
  call assertTrue(st == 0, 'elements status', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 60) )
  if (anyExceptions()) return
#line 61 "/work/wt12/test/test_kepler.pf"
#line 61 "/work/wt12/test/test_kepler.pf"
  call assertEqual(0.9_wp, e, 1e-14_wp, 'e', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 61) )
  if (anyExceptions()) return
#line 62 "/work/wt12/test/test_kepler.pf"
#line 62 "/work/wt12/test/test_kepler.pf"
  call assertEqual(100.0_wp / 19.0_wp, a, 1e-13_wp, 'a', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 62) )
  if (anyExceptions()) return
#line 63 "/work/wt12/test/test_kepler.pf"
#line 63 "/work/wt12/test/test_kepler.pf"
  call assertEqual(-0.095_wp, kepler_energy(q, v), 1e-15_wp, 'E0', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 63) )
  if (anyExceptions()) return
#line 64 "/work/wt12/test/test_kepler.pf"
#line 64 "/work/wt12/test/test_kepler.pf"
  call assertEqual(p, pp, 1e-12_wp, 'period', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 64) )
  if (anyExceptions()) return
#line 65 "/work/wt12/test/test_kepler.pf"
#line 65 "/work/wt12/test/test_kepler.pf"
  call assertEqual(1.0_wp, kepler_angular_momentum_2d(q, v), 1e-15_wp, 'L', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 65) )
  if (anyExceptions()) return
#line 66 "/work/wt12/test/test_kepler.pf"
        call kepler_elements([1.0_wp, 0.0_wp], [0.0_wp, 2.0_wp], a, e, pp, st)
#line 67 "/work/wt12/test/test_kepler.pf"
  call assertTrue(st == FSYM_ERR_NOT_ELLIPTIC, 'unbound orbit refused', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 67) )
  if (anyExceptions()) return
#line 68 "/work/wt12/test/test_kepler.pf"
    end subroutine test_elements

    !> kepler: exact solution conserves E, L, LRL and has dq/dt = v
    !@test
    subroutine test_exact()
        real(wp) :: q0(2), v0(2), q(2), v(2), qp(2), vp(2), qm(2), vm(2), p, t, l0(2), l(2)
        real(wp), parameter :: dt = 1e-4_wp
        integer :: k, st
        logical :: ok
        call kepler_paper_orbit(q0, v0, p)
        call kepler_lrl(q0, v0, l0)
        do k = 1, 13
            t = p * k / 13.0_wp + 0.37_wp * k
            call kepler_exact(q0, v0, t, q, v, st)
#line 82 "/work/wt12/test/test_kepler.pf"
  call assertTrue(st == 0, 'exact status', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 82) )
  if (anyExceptions()) return
#line 83 "/work/wt12/test/test_kepler.pf"
#line 83 "/work/wt12/test/test_kepler.pf"
  call assertEqual(-0.095_wp, kepler_energy(q, v), 1e-13_wp, 'exact E', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 83) )
  if (anyExceptions()) return
#line 84 "/work/wt12/test/test_kepler.pf"
#line 84 "/work/wt12/test/test_kepler.pf"
  call assertEqual(1.0_wp, kepler_angular_momentum_2d(q, v), 1e-12_wp, 'exact L', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 84) )
  if (anyExceptions()) return
#line 85 "/work/wt12/test/test_kepler.pf"
            call kepler_lrl(q, v, l)
#line 86 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs(l - l0)) < 1e-12_wp, 'exact LRL', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 86) )
  if (anyExceptions()) return
#line 87 "/work/wt12/test/test_kepler.pf"
            call kepler_exact(q0, v0, t + dt, qp, vp, st)
            call kepler_exact(q0, v0, t - dt, qm, vm, st)
#line 89 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs((qp - qm) / (2 * dt) - v)) < 1e-6_wp, 'exact dq/dt = v', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/wt12/test/test_kepler.pf"
            ok = maxval(abs((vp - vm) / (2 * dt) + q / sum(q**2)**1.5_wp)) < 1e-5_wp
#line 91 "/work/wt12/test/test_kepler.pf"
  call assertTrue(ok, 'exact dv/dt = a', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 91) )
  if (anyExceptions()) return
#line 92 "/work/wt12/test/test_kepler.pf"
        end do
        call kepler_exact(q0, v0, p, q, v, st)
#line 94 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs(q - q0)) < 1e-10_wp, 'exact returns after one period', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 94) )
  if (anyExceptions()) return
#line 95 "/work/wt12/test/test_kepler.pf"
        call kepler_exact(q0, v0, 0.5_wp * p, q, v, st)
#line 96 "/work/wt12/test/test_kepler.pf"
  call assertEqual(-10.0_wp / 19.0_wp, q(1), 1e-9_wp, 'pericentre at P/2 is (-a(1-e), 0)', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 96) )
  if (anyExceptions()) return
#line 97 "/work/wt12/test/test_kepler.pf"
    end subroutine test_exact

    !> kepler: exact solution agrees with a fine A6 integration
    !@test
    subroutine test_exact_vs_a6()
        type(kepler_model_t) :: m
        type(integrator_t) :: it
        real(wp) :: q(2, 1), v(2, 1), q0(2), v0(2), qe(2), ve(2), p
        integer :: st
        call kepler_paper_orbit(q0, v0, p)
        q(:, 1) = q0; v(:, 1) = v0
        call it%init_by_name('A6', m, 2, 1, st)
        call it%run(m, q, v, p / 20000.0_wp, 7000_ik, st)
        call kepler_exact(q0, v0, it%time(), qe, ve, st)
#line 111 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs(q(:, 1) - qe)) < 1e-9_wp, 'A6 vs exact position', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 111) )
  if (anyExceptions()) return
#line 112 "/work/wt12/test/test_kepler.pf"
#line 112 "/work/wt12/test/test_kepler.pf"
  call assertTrue(maxval(abs(v(:, 1) - ve)) < 1e-9_wp, 'A6 vs exact velocity', &
 & location=SourceLocation( &
 & 'test_kepler.pf', &
 & 112) )
  if (anyExceptions()) return
#line 113 "/work/wt12/test/test_kepler.pf"
    end subroutine test_exact_vs_a6

end module test_kepler


module Wraptest_kepler
   use FUnit
   use test_kepler
   implicit none
   private

contains


end module Wraptest_kepler

function test_kepler_suite() result(suite)
   use FUnit
   use test_kepler
   use Wraptest_kepler
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_kepler_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_force', &
      test_force))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_gradient', &
      test_gradient))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_elements', &
      test_elements))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_exact', &
      test_exact))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_exact_vs_a6', &
      test_exact_vs_a6))
   call suite%addTest(t)


end function test_kepler_suite

