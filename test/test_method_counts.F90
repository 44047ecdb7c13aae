!> Bookkeeping of every method (each method its own test case): the scheme table of each
!> catalogue entry is consistent (drift and kick coefficients sum to 1, symmetric, order),
!> and the force and gradient evaluations measured over 100 steps match the table, as do
!> the splitting and forward flags.
module test_method_counts
    use fsym
    use funit
    use fsym_test_methods, only: method_param_t, method_case_t
    implicit none

    !@testParameter
    type, extends(method_param_t) :: counts_param_t
    end type counts_param_t

    !@testCase(constructor=counts_case)
    type, extends(method_case_t) :: counts_case_t
    end type counts_case_t

contains

    !> The cases of a list of labels.
    function params_of(names) result(params)
        character(len=*), intent(in) :: names(:)
        type(counts_param_t), allocatable :: params(:)
        integer :: k
        params = [(counts_param_t(method=names(k)), k = 1, size(names))]
    end function params_of

    !> The case of one method.
    function counts_case(param) result(tc)
        type(counts_param_t), intent(in) :: param
        type(counts_case_t) :: tc
        tc%method = param%method
    end function counts_case

    !> scheme: the catalogue entry builds and is consistent
    !@test(testParameters={params_of(fsym_catalogue())})
    subroutine test_table(this)
        class(counts_case_t), intent(inout) :: this
        type(scheme_t) :: s
        integer :: st
        character(len=256) :: msg
        character(len=:), allocatable :: name
        name = trim(this%method)
        call fsym_scheme_by_name(name, s, st, msg)
#line 46 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(0, st, 'cannot build '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 46) )
  if (anyExceptions()) return
#line 47 "/work/wt12/test/test_method_counts.pf"
#line 47 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(1.0_wp, sum(s%c, mask=s%op == OP_DRIFT), 1.0e-13_wp, name//' drift sum', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 47) )
  if (anyExceptions()) return
#line 48 "/work/wt12/test/test_method_counts.pf"
#line 48 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(1.0_wp, sum(s%c, mask=s%op /= OP_DRIFT), 1.0e-13_wp, name//' kick sum', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 48) )
  if (anyExceptions()) return
#line 49 "/work/wt12/test/test_method_counts.pf"
#line 49 "/work/wt12/test/test_method_counts.pf"
  call assertTrue(s%symmetric, name//' should be symmetric', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/wt12/test/test_method_counts.pf"
#line 50 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(merge(2, 4, name == 'T2'), s%order, name//' order', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/wt12/test/test_method_counts.pf"
    end subroutine test_table

    !> counts: measured evaluations per step match the table; splitting and forward flags
    !@test(testParameters={params_of(fsym_method_names())})
    subroutine test_evaluations(this)
        class(counts_case_t), intent(inout) :: this
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        type(scheme_t) :: sc
        real(wp) :: q(2, 1), v(2, 1), p
        integer(ik) :: f1, g1
        integer :: st
        character(len=256) :: msg
        character(len=:), allocatable :: name
        name = trim(this%method)
        call kepler_paper_orbit(q(:, 1), v(:, 1), p)
        call fsym_new_stepper(name, kep, 2, 1, s, st, msg)
#line 68 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(0, st, 'cannot make '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 68) )
  if (anyExceptions()) return
#line 69 "/work/wt12/test/test_method_counts.pf"
        call s%step(kep, q, v, p / 1000, st)
        f1 = s%force_evaluations(); g1 = s%gradient_evaluations()
        call s%run(kep, q, v, p / 1000, 100_ik, st)
#line 72 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(0, st, name//': run failed', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 72) )
  if (anyExceptions()) return
#line 73 "/work/wt12/test/test_method_counts.pf"
#line 73 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(100 * s%forces_per_step(), s%force_evaluations() - f1, name//': forces', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 73) )
  if (anyExceptions()) return
#line 74 "/work/wt12/test/test_method_counts.pf"
#line 74 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(100 * s%gradients_per_step(), s%gradient_evaluations() - g1, name//': grads', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 74) )
  if (anyExceptions()) return
#line 75 "/work/wt12/test/test_method_counts.pf"
        if (name == 'RKN') then
#line 76 "/work/wt12/test/test_method_counts.pf"
  call assertFalse(s%is_splitting(), 'RKN is not a splitting method', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 76) )
  if (anyExceptions()) return
#line 77 "/work/wt12/test/test_method_counts.pf"
#line 77 "/work/wt12/test/test_method_counts.pf"
  call assertEqual(3, s%forces_per_step(), 'RKN: three forces per step', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 77) )
  if (anyExceptions()) return
#line 78 "/work/wt12/test/test_method_counts.pf"
        else
            call fsym_scheme_by_name(name, sc)
#line 80 "/work/wt12/test/test_method_counts.pf"
  call assertTrue(s%is_splitting(), name//' is a splitting method', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 80) )
  if (anyExceptions()) return
#line 81 "/work/wt12/test/test_method_counts.pf"
#line 81 "/work/wt12/test/test_method_counts.pf"
  call assertTrue(s%is_forward() .eqv. sc%forward, name//': forward flag as in the table', &
 & location=SourceLocation( &
 & 'test_method_counts.pf', &
 & 81) )
  if (anyExceptions()) return
#line 82 "/work/wt12/test/test_method_counts.pf"
        end if
    end subroutine test_evaluations

end module test_method_counts

module Wraptest_method_counts
   use FUnit
   use test_method_counts
   implicit none
   private

   public :: WrapUserTestCase
   public :: makeCustomTest
   type, extends(counts_case_t) :: WrapUserTestCase
      procedure(userTestMethod), nopass, pointer :: testMethodPtr
   contains
      procedure :: runMethod
   end type WrapUserTestCase

   abstract interface
     subroutine userTestMethod(this)
        use test_method_counts
        class (counts_case_t), intent(inout) :: this
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
      type (counts_param_t), intent(in) :: testParameter
      aTest%counts_case_t = counts_case(testParameter)

      aTest%testMethodPtr => testMethod
#ifdef INTEL_13
      p => aTest
      call p%setName(methodName)
#else
      call aTest%setName(methodName)
#endif
      call aTest%setTestParameter(testParameter)
   end function makeCustomTest

end module Wraptest_method_counts

function test_method_counts_suite() result(suite)
   use FUnit
   use test_method_counts
   use Wraptest_method_counts
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   type (counts_param_t), allocatable :: testParameters(:)
   type (counts_param_t) :: testParameter
   integer :: iParam, iCase 
   integer, allocatable :: cases(:) 
 
   suite = TestSuite('test_method_counts_suite')

   testParameters = params_of(fsym_catalogue())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_table', test_table, testParameter))
   end do

   testParameters = params_of(fsym_method_names())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_evaluations', test_evaluations, testParameter))
   end do


end function test_method_counts_suite

