!> Linear stability of every method (each method its own test case): the stage-array
!> oscillator map against the integrator's step, the stability limit x* against direct
!> integration of the oscillator just below and just above it, and runs through near
!> collisions that end refused or finite, never in NaN.
module test_method_stability
    use fsym
    use fsym_stability
    use fsym_stability_runs
    use funit
    use fsym_test_methods, only: method_param_t, method_case_t
    implicit none

    !@testParameter
    type, extends(method_param_t) :: stability_param_t
    end type stability_param_t

    !@testCase(constructor=stability_case)
    type, extends(method_case_t) :: stability_case_t
    end type stability_case_t

contains

    !> The cases of a list of labels.
    function params_of(names) result(params)
        character(len=*), intent(in) :: names(:)
        type(stability_param_t), allocatable :: params(:)
        integer :: k
        params = [(stability_param_t(method=names(k)), k = 1, size(names))]
    end function params_of

    !> The case of one method.
    function stability_case(param) result(tc)
        type(stability_param_t), intent(in) :: param
        type(stability_case_t) :: tc
        tc%method = param%method
    end function stability_case

    !> stability: the stage-array map of the oscillator equals the integrator's step
    !@test(testParameters={params_of(fsym_catalogue())})
    subroutine test_map(this)
        class(stability_case_t), intent(inout) :: this
        type(oscillator_model_t) :: osc
        type(scheme_t) :: s
        real(wp) :: m(2, 2), mm(2, 2)
        integer :: st
        character(len=256) :: msg
        character(len=:), allocatable :: name
        name = trim(this%method)
        call fsym_scheme_by_name(name, s, st, msg)
#line 50 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(0, st, 'scheme '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/wt12/test/test_method_stability.pf"
        call fsym_oscillator_map(s, 0.7_wp, m)
        call fsym_linear_step_map(name, osc, 1, 1, 0.7_wp, mm, st, msg)
#line 53 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(0, st, 'map of '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 53) )
  if (anyExceptions()) return
#line 54 "/work/wt12/test/test_method_stability.pf"
#line 54 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(m, mm, 1.0e-13_wp, 'stage-array map and step differ for '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 54) )
  if (anyExceptions()) return
#line 55 "/work/wt12/test/test_method_stability.pf"
#line 55 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(1.0_wp, m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1), 1.0e-13_wp, 'det of '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 55) )
  if (anyExceptions()) return
#line 56 "/work/wt12/test/test_method_stability.pf"
    end subroutine test_map

    !> stability: x* vs integration of the oscillator (omega = 1, h = x) just below/above
    !@test(testParameters={params_of(fsym_method_names())})
    subroutine test_limit(this)
        class(stability_case_t), intent(inout) :: this
        type(scheme_t) :: s
        type(oscillator_model_t) :: osc
        real(wp) :: xs, xn, below, above
        integer :: st
        character(len=256) :: msg
        character(len=120) :: line
        character(len=:), allocatable :: name
        name = trim(this%method)
        if (name == 'RKN') then
            call fsym_stable_step('RKN', osc, 1, 1, 6.0_wp, xs, st, msg)
#line 72 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(0, st, 'RKN stable step: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 72) )
  if (anyExceptions()) return
#line 73 "/work/wt12/test/test_method_stability.pf"
            xn = 2.0_wp * xs
        else
            call fsym_scheme_by_name(name, s, st, msg)
#line 76 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(0, st, 'scheme '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 76) )
  if (anyExceptions()) return
#line 77 "/work/wt12/test/test_method_stability.pf"
            call fsym_stability_interval(s, xs, xnext=xn)
        end if
        ! just above: inside the first instability window, however narrow
        call fsym_oscillator_growth(name, 0.99_wp * xs, 20000, below)
        call fsym_oscillator_growth(name, xs + min(0.01_wp * xs, 0.5_wp * (xn - xs)), 20000, &
                                    above)
        write (line, '(a,a,f9.6,a,es9.2,a,es9.2)') name, ': x* =', xs, ', growth below', &
            below, ', above', above
#line 85 "/work/wt12/test/test_method_stability.pf"
  call assertTrue(below < 1.0e2_wp, 'not bounded below x*: '//trim(line), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 85) )
  if (anyExceptions()) return
#line 86 "/work/wt12/test/test_method_stability.pf"
#line 86 "/work/wt12/test/test_method_stability.pf"
  call assertTrue(above > 1.0e6_wp, 'not growing above x*: '//trim(line), &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 86) )
  if (anyExceptions()) return
#line 87 "/work/wt12/test/test_method_stability.pf"
    end subroutine test_limit

    !> stability: through pericentre 1e-9, from r = 0 and in radial infall, a run ends
    !> refused with a status and a message, or finite; its clock reads n h
    !@test(testParameters={params_of(fsym_method_names())})
    subroutine test_collision(this)
        class(stability_case_t), intent(inout) :: this
        type(kepler_run_t) :: run
        real(wp) :: q0(2, 3), v0(2, 3)
        integer :: c
        character(len=:), allocatable :: name
        name = trim(this%method)
        call kepler_elliptic_orbit(1.0_wp - 1.0e-9_wp, q0(:, 1), v0(:, 1))
        q0(:, 2) = 0.0_wp; v0(:, 2) = [0.0_wp, 1.0_wp]
        q0(:, 3) = [1.0_wp, 0.0_wp]; v0(:, 3) = 0.0_wp
        do c = 1, 3
            call fsym_kepler_run(name, q0(:, c), v0(:, c), 200_ik, 1_ik, run)
            if (run%outcome == RUN_REFUSED) then
#line 105 "/work/wt12/test/test_method_stability.pf"
  call assertTrue(run%stat /= 0, 'refused without status: '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 105) )
  if (anyExceptions()) return
#line 106 "/work/wt12/test/test_method_stability.pf"
#line 106 "/work/wt12/test/test_method_stability.pf"
  call assertTrue(len_trim(run%msg) > 0, 'refused without message: '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 106) )
  if (anyExceptions()) return
#line 107 "/work/wt12/test/test_method_stability.pf"
            end if
#line 108 "/work/wt12/test/test_method_stability.pf"
  call assertTrue(run%finite, 'non-finite state kept: '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 108) )
  if (anyExceptions()) return
#line 109 "/work/wt12/test/test_method_stability.pf"
#line 109 "/work/wt12/test/test_method_stability.pf"
  call assertEqual(real(run%steps, wp) * (2.0_wp * FSYM_PI / 200.0_wp), run%time, 0.0_wp, 'time is not n h: '//name, &
 & location=SourceLocation( &
 & 'test_method_stability.pf', &
 & 109) )
  if (anyExceptions()) return
#line 110 "/work/wt12/test/test_method_stability.pf"
        end do
    end subroutine test_collision

end module test_method_stability

module Wraptest_method_stability
   use FUnit
   use test_method_stability
   implicit none
   private

   public :: WrapUserTestCase
   public :: makeCustomTest
   type, extends(stability_case_t) :: WrapUserTestCase
      procedure(userTestMethod), nopass, pointer :: testMethodPtr
   contains
      procedure :: runMethod
   end type WrapUserTestCase

   abstract interface
     subroutine userTestMethod(this)
        use test_method_stability
        class (stability_case_t), intent(inout) :: this
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
      type (stability_param_t), intent(in) :: testParameter
      aTest%stability_case_t = stability_case(testParameter)

      aTest%testMethodPtr => testMethod
#ifdef INTEL_13
      p => aTest
      call p%setName(methodName)
#else
      call aTest%setName(methodName)
#endif
      call aTest%setTestParameter(testParameter)
   end function makeCustomTest

end module Wraptest_method_stability

function test_method_stability_suite() result(suite)
   use FUnit
   use test_method_stability
   use Wraptest_method_stability
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   type (stability_param_t), allocatable :: testParameters(:)
   type (stability_param_t) :: testParameter
   integer :: iParam, iCase 
   integer, allocatable :: cases(:) 
 
   suite = TestSuite('test_method_stability_suite')

   testParameters = params_of(fsym_catalogue())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_map', test_map, testParameter))
   end do

   testParameters = params_of(fsym_method_names())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_limit', test_limit, testParameter))
   end do

   testParameters = params_of(fsym_method_names())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_collision', test_collision, testParameter))
   end do


end function test_method_stability_suite

