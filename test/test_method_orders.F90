!> Measured order of every method (each method its own test case): the phase-space error
!> after one period of the e = 0.9 Kepler orbit at h = P/3200, P/6400, P/12800, and the
!> differences of Henon-Heiles states at time 10 for h = 0.2, 0.1, 0.05, 0.025. T2 is of
!> order 2, every other method of order 4; the finest pair must give the order within 0.25
!> (Kepler) and 0.2 (Henon-Heiles).
module test_method_orders
    use fsym
    use funit
    use fsym_test_methods, only: method_param_t, method_case_t
    implicit none

    !@testParameter
    type, extends(method_param_t) :: order_param_t
    end type order_param_t

    !@testCase(constructor=order_case)
    type, extends(method_case_t) :: order_case_t
    end type order_case_t

contains

    !> One case per method (the catalogue and RKN).
    function method_params() result(params)
        type(order_param_t), allocatable :: params(:)
        character(len=FSYM_NAME_LEN), allocatable :: names(:)
        integer :: k
        names = fsym_method_names()
        params = [(order_param_t(method=names(k)), k = 1, size(names))]
    end function method_params

    !> The case of one method.
    function order_case(param) result(tc)
        type(order_param_t), intent(in) :: param
        type(order_case_t) :: tc
        tc%method = param%method
    end function order_case

    !> The expected order: 2 for T2, 4 for the others.
    real(wp) function expected_order(name)
        character(len=*), intent(in) :: name
        expected_order = merge(2.0_wp, 4.0_wp, name == 'T2')
    end function expected_order

    !> Phase-space error after one period of the paper orbit at h = P/nper.
    real(wp) function kepler_error(name, nper) result(e)
        character(len=*), intent(in) :: name
        integer, intent(in) :: nper
        type(kepler_model_t) :: m
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), p, q0(2), v0(2)
        integer :: st
        character(len=256) :: msg
        e = huge(1.0_wp)
        call kepler_paper_orbit(q0, v0, p)
        q(:, 1) = q0; v(:, 1) = v0
        call fsym_new_stepper(name, m, 2, 1, s, st, msg)
#line 57 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(0, st, 'cannot make '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 57) )
  if (anyExceptions()) return
#line 58 "/work/wt12/test/test_method_orders.pf"
        call s%run(m, q, v, p / nper, int(nper, ik), st, msg)
#line 59 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(0, st, name//': run failed: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 59) )
  if (anyExceptions()) return
#line 60 "/work/wt12/test/test_method_orders.pf"
        e = max(maxval(abs(q(:, 1) - q0)), maxval(abs(v(:, 1) - v0)) * 10.0_wp)
    end function kepler_error

    !> order: the method on the e = 0.9 Kepler orbit (P/3200..P/12800)
    !@test(testParameters={method_params()})
    subroutine test_kepler(this)
        class(order_case_t), intent(inout) :: this
        integer, parameter :: nper(3) = [3200, 6400, 12800]
        real(wp) :: e(3), p(2)
        character(len=160) :: line
        integer :: j
        do j = 1, 3
            e(j) = kepler_error(trim(this%method), nper(j))
            if (anyExceptions()) return
        end do
        p = fsym_observed_orders(1.0_wp / nper, e)
        write (line, '(a,a,a,3es10.2,a,2f7.3)') 'order on Kepler of ', trim(this%method), &
            ': errors', e, ', orders', p
#line 78 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(expected_order(this%method), p(2), 0.25_wp, trim(line), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 78) )
  if (anyExceptions()) return
#line 79 "/work/wt12/test/test_method_orders.pf"
    end subroutine test_kepler

    !> Henon-Heiles state after time 10 at step h.
    subroutine hh_run(name, h, z)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: h
        real(wp), intent(out) :: z(4)
        type(henon_heiles_model_t) :: m
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1)
        integer :: st
        character(len=256) :: msg
        z = 0.0_wp
        q(:, 1) = [0.1_wp, -0.1_wp]; v(:, 1) = [0.3_wp, 0.2_wp]
        call fsym_new_stepper(name, m, 2, 1, s, st, msg)
#line 94 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(0, st, 'cannot make '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 94) )
  if (anyExceptions()) return
#line 95 "/work/wt12/test/test_method_orders.pf"
        call s%run(m, q, v, h, nint(10.0_wp / h, ik), st, msg)
#line 96 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(0, st, name//': Henon-Heiles run failed: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 96) )
  if (anyExceptions()) return
#line 97 "/work/wt12/test/test_method_orders.pf"
        z = [q(:, 1), v(:, 1)]
    end subroutine hh_run

    !> order: the method on Henon-Heiles (h = 0.2..0.025)
    !@test(testParameters={method_params()})
    subroutine test_henon_heiles(this)
        class(order_case_t), intent(inout) :: this
        real(wp), parameter :: h(4) = [0.2_wp, 0.1_wp, 0.05_wp, 0.025_wp]
        real(wp) :: z(4, 4), d(3), p(2)
        character(len=160) :: line
        integer :: j
        do j = 1, 4
            call hh_run(trim(this%method), h(j), z(:, j))
            if (anyExceptions()) return
        end do
        do j = 1, 3
            d(j) = maxval(abs(z(:, j) - z(:, j + 1)))
        end do
        p = fsym_observed_orders(h(1:3), d)
        write (line, '(a,a,a,3es10.2,a,2f7.3)') 'order on Henon-Heiles of ', &
            trim(this%method), ': differences', d, ', orders', p
#line 118 "/work/wt12/test/test_method_orders.pf"
  call assertEqual(expected_order(this%method), p(2), 0.2_wp, trim(line), &
 & location=SourceLocation( &
 & 'test_method_orders.pf', &
 & 118) )
  if (anyExceptions()) return
#line 119 "/work/wt12/test/test_method_orders.pf"
    end subroutine test_henon_heiles

end module test_method_orders

module Wraptest_method_orders
   use FUnit
   use test_method_orders
   implicit none
   private

   public :: WrapUserTestCase
   public :: makeCustomTest
   type, extends(order_case_t) :: WrapUserTestCase
      procedure(userTestMethod), nopass, pointer :: testMethodPtr
   contains
      procedure :: runMethod
   end type WrapUserTestCase

   abstract interface
     subroutine userTestMethod(this)
        use test_method_orders
        class (order_case_t), intent(inout) :: this
     end subroutine userTestMethod
   end interface

contains

   subroutine runMethod(this)
      class (WrapUserTestCase), intent(inout) :: this

      call this%testMethodPtr(this)
   end subroutine runMethod

   function makeCustomTest(methodName, testMethod, testParameter) result(aTest)
      type (WrapUserTestCase) :: aTest
      character(len=*), intent(in) :: methodName
      procedure(userTestMethod) :: testMethod
      type (order_param_t), intent(in) :: testParameter
      aTest%order_case_t = order_case(testParameter)

      aTest%testMethodPtr => testMethod
#ifdef INTEL_13
      p => aTest
      call p%setName(methodName)
#else
      call aTest%setName(methodName)
#endif
      call aTest%setTestParameter(testParameter)
   end function makeCustomTest

end module Wraptest_method_orders

function test_method_orders_suite() result(suite)
   use FUnit
   use test_method_orders
   use Wraptest_method_orders
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   type (order_param_t), allocatable :: testParameters(:)
   type (order_param_t) :: testParameter
   integer :: iParam, iCase 
   integer, allocatable :: cases(:) 
 
   suite = TestSuite('test_method_orders_suite')

   testParameters = method_params()

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_kepler', test_kepler, testParameter))
   end do

   testParameters = method_params()

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_henon_heiles', test_henon_heiles, testParameter))
   end do


end function test_method_orders_suite

