!> Geometric properties of every method (each method its own test case): the symplecticity
!> defect |M^T J M - J| of the one-step map on Henon-Heiles and near the pericentre of the
!> e = 0.9 Kepler orbit, the h^5 scaling of the defect of the extrapolated methods, and time
!> reversibility under h, -h.
module test_method_geometry
    use fsym
    use funit
    use fsym_test_methods, only: method_param_t, method_case_t
    implicit none

    !@testParameter
    type, extends(method_param_t) :: geometry_param_t
    end type geometry_param_t

    !@testCase(constructor=geometry_case)
    type, extends(method_case_t) :: geometry_case_t
    end type geometry_case_t

contains

    !> The cases of a list of labels.
    function params_of(names) result(params)
        character(len=*), intent(in) :: names(:)
        type(geometry_param_t), allocatable :: params(:)
        integer :: k
        params = [(geometry_param_t(method=names(k)), k = 1, size(names))]
    end function params_of

    !> The case of one method.
    function geometry_case(param) result(tc)
        type(geometry_param_t), intent(in) :: param
        type(geometry_case_t) :: tc
        tc%method = param%method
    end function geometry_case

    !> Symplecticity defect of one step of `name` from (q, v) at step h.
    real(wp) function defect_of(name, model, q, v, h) result(defect)
        character(len=*), intent(in) :: name
        class(force_model_t), intent(inout) :: model
        real(wp), intent(in) :: q(:, :), v(:, :), h
        class(stepper_t), allocatable :: s
        real(wp) :: jac(2 * size(q), 2 * size(q))
        integer :: st
        character(len=256) :: msg
        defect = huge(1.0_wp)
        call fsym_new_stepper(name, model, size(q, 1), size(q, 2), s, st, msg)
#line 47 "/work/wt12/test/test_method_geometry.pf"
  call assertEqual(0, st, 'cannot make '//name//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 47) )
  if (anyExceptions()) return
#line 48 "/work/wt12/test/test_method_geometry.pf"
        call fsym_step_jacobian(s, model, q, v, h, jac, st, msg)
#line 49 "/work/wt12/test/test_method_geometry.pf"
  call assertEqual(0, st, 'jacobian: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/wt12/test/test_method_geometry.pf"
        defect = fsym_symplectic_defect(jac)
    end function defect_of

    !> symplectic: M^T J M = J for a splitting method (for the extrapolated ones on Kepler
    !> only, whose force is central); not for RKN
    !@test(testParameters={params_of(fsym_method_names())})
    subroutine test_symplectic(this)
        class(geometry_case_t), intent(inout) :: this
        type(henon_heiles_model_t) :: hh
        type(kepler_model_t) :: kep
        type(scheme_t) :: s
        real(wp) :: dh, dk, q(2, 1), v(2, 1), p, q0(2), v0(2)
        character(len=160) :: line
        logical :: exact_on_kepler, exact_on_hh
        integer :: st
        call kepler_paper_orbit(q0, v0, p)
        ! near the pericentre, where the force varies fastest
        call kepler_exact(q0, v0, 0.48_wp * p, q(:, 1), v(:, 1), st)
        ! a point where the Henon-Heiles torque x^3 - 3xy^2 is not small
        dh = defect_of(trim(this%method), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                       reshape([0.0_wp, 0.2_wp], [2, 1]), 0.2_wp)
        dk = defect_of(trim(this%method), kep, q, v, p / 200.0_wp)
        if (anyExceptions()) return
        write (line, '(a,a,a,es10.2,a,es10.2)') 'symplectic defect of ', trim(this%method), &
            ': Henon-Heiles', dh, ', Kepler', dk
        if (this%method == 'RKN') then
            exact_on_hh = .false.; exact_on_kepler = .false.
        else
            call fsym_scheme_by_name(trim(this%method), s)
            exact_on_hh = s%symplectic
            exact_on_kepler = .true.          ! extrapolated forms are exact for central forces
        end if
        if (exact_on_hh) then
#line 83 "/work/wt12/test/test_method_geometry.pf"
  call assertTrue(dh < 1e-11_wp, trim(line)//' (Henon-Heiles: should be symplectic)', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 83) )
  if (anyExceptions()) return
#line 84 "/work/wt12/test/test_method_geometry.pf"
        else
#line 85 "/work/wt12/test/test_method_geometry.pf"
  call assertTrue(dh > 1e-10_wp, trim(line)//' (Henon-Heiles: should not be exactly)', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 85) )
  if (anyExceptions()) return
#line 86 "/work/wt12/test/test_method_geometry.pf"
        end if
        if (exact_on_kepler) then
#line 88 "/work/wt12/test/test_method_geometry.pf"
  call assertTrue(dk < 1e-11_wp, trim(line)//' (Kepler: should be symplectic)', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 88) )
  if (anyExceptions()) return
#line 89 "/work/wt12/test/test_method_geometry.pf"
        else
#line 90 "/work/wt12/test/test_method_geometry.pf"
  call assertTrue(dk > 1e-9_wp, trim(line)//' (RKN: should not be symplectic)', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 90) )
  if (anyExceptions()) return
#line 91 "/work/wt12/test/test_method_geometry.pf"
        end if
    end subroutine test_symplectic

    !> symplectic: the extrapolated methods' defect on Henon-Heiles falls as h^5
    !@test(testParameters={params_of(["A' ", "C' ", "A5'", "A6'"])})
    subroutine test_extrapolated_defect(this)
        class(geometry_case_t), intent(inout) :: this
        type(henon_heiles_model_t) :: hh
        real(wp) :: d1, d2, p
        character(len=120) :: line
        d1 = defect_of(trim(this%method), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                       reshape([0.0_wp, 0.2_wp], [2, 1]), 0.2_wp)
        d2 = defect_of(trim(this%method), hh, reshape([0.3_wp, 0.0_wp], [2, 1]), &
                       reshape([0.0_wp, 0.2_wp], [2, 1]), 0.1_wp)
        if (anyExceptions()) return
        p = log(d1 / d2) / log(2.0_wp)
        write (line, '(a,a,a,2es10.2,a,f6.2)') 'extrapolated defect of ', trim(this%method), &
            ' at h = 0.2, 0.1:', d1, d2, ', order', p
#line 109 "/work/wt12/test/test_method_geometry.pf"
  call assertEqual(5.0_wp, p, 0.5_wp, trim(line), &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 109) )
  if (anyExceptions()) return
#line 110 "/work/wt12/test/test_method_geometry.pf"
    end subroutine test_extrapolated_defect

    !> reversible: a symmetric method returns to the start under h, -h
    !@test(testParameters={params_of(fsym_catalogue())})
    subroutine test_reversible(this)
        class(geometry_case_t), intent(inout) :: this
        type(kepler_model_t) :: kep
        class(stepper_t), allocatable :: s
        real(wp) :: q(2, 1), v(2, 1), defect
        integer :: st
        character(len=256) :: msg
        q(:, 1) = [0.8_wp, 0.3_wp]; v(:, 1) = [-0.2_wp, 1.1_wp]
        call fsym_new_stepper(trim(this%method), kep, 2, 1, s, st, msg)
#line 123 "/work/wt12/test/test_method_geometry.pf"
  call assertEqual(0, st, 'cannot make '//trim(this%method)//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 123) )
  if (anyExceptions()) return
#line 124 "/work/wt12/test/test_method_geometry.pf"
        call fsym_reversibility_defect(s, kep, q, v, 0.05_wp, defect, st)
#line 125 "/work/wt12/test/test_method_geometry.pf"
  call assertEqual(0, st, trim(this%method)//': reversibility run failed', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 125) )
  if (anyExceptions()) return
#line 126 "/work/wt12/test/test_method_geometry.pf"
#line 126 "/work/wt12/test/test_method_geometry.pf"
  call assertTrue(defect < 1e-14_wp, trim(this%method)//' is not reversible', &
 & location=SourceLocation( &
 & 'test_method_geometry.pf', &
 & 126) )
  if (anyExceptions()) return
#line 127 "/work/wt12/test/test_method_geometry.pf"
    end subroutine test_reversible

end module test_method_geometry

module Wraptest_method_geometry
   use FUnit
   use test_method_geometry
   implicit none
   private

   public :: WrapUserTestCase
   public :: makeCustomTest
   type, extends(geometry_case_t) :: WrapUserTestCase
      procedure(userTestMethod), nopass, pointer :: testMethodPtr
   contains
      procedure :: runMethod
   end type WrapUserTestCase

   abstract interface
     subroutine userTestMethod(this)
        use test_method_geometry
        class (geometry_case_t), intent(inout) :: this
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
      type (geometry_param_t), intent(in) :: testParameter
      aTest%geometry_case_t = geometry_case(testParameter)

      aTest%testMethodPtr => testMethod
#ifdef INTEL_13
      p => aTest
      call p%setName(methodName)
#else
      call aTest%setName(methodName)
#endif
      call aTest%setTestParameter(testParameter)
   end function makeCustomTest

end module Wraptest_method_geometry

function test_method_geometry_suite() result(suite)
   use FUnit
   use test_method_geometry
   use Wraptest_method_geometry
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   type (geometry_param_t), allocatable :: testParameters(:)
   type (geometry_param_t) :: testParameter
   integer :: iParam, iCase 
   integer, allocatable :: cases(:) 
 
   suite = TestSuite('test_method_geometry_suite')

   testParameters = params_of(fsym_method_names())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_symplectic', test_symplectic, testParameter))
   end do

   testParameters = params_of(["A' ", "C' ", "A5'", "A6'"])

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_extrapolated_defect', test_extrapolated_defect, testParameter))
   end do

   testParameters = params_of(fsym_catalogue())

   do iParam = 1, size(testParameters)
      testParameter = testParameters(iParam)
   call suite%addTest(makeCustomTest('test_reversible', test_reversible, testParameter))
   end do


end function test_method_geometry_suite

