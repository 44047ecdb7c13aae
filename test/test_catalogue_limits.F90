!> Label limits of the catalogue (issue 11, item 1): labels whose number overflows an integer,
!> an AN table too large for memory, and a huge parameter are refused with a status and a
!> message naming what was typed; the host program is never stopped and the scheme is left
!> as it was. Every case here stopped the program or misreported before the limits existed.
module test_catalogue_limits
    use funit
    use fsym
    implicit none

contains

    !> Build FR into `s`, then ask for `label`; expect `code`, a message containing `text`,
    !> and `s` still FR.
    subroutine expect_refused(label, code, text)
        character(len=*), intent(in) :: label, text
        integer, intent(in) :: code
        type(scheme_t) :: s
        integer :: st
        character(len=200) :: msg
        character(len=40) :: shown
        shown = label
        s = fsym_scheme_fr()
        msg = ''
        st = -1
        call fsym_scheme_by_name(label, s, st, msg)
#line 26 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(code, st, 'status of "'//trim(shown)//'": '//trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 26) )
  if (anyExceptions()) return
#line 27 "/work/wt10b/test/test_catalogue_limits.pf"
#line 27 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertTrue(index(msg, text) > 0, 'message of "'//trim(shown)//'" lacks "'//text//'": '//trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 27) )
  if (anyExceptions()) return
#line 28 "/work/wt10b/test/test_catalogue_limits.pf"
#line 28 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual('FR', s%name, 'scheme changed by the refused label '//trim(shown), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 28) )
  if (anyExceptions()) return
#line 29 "/work/wt10b/test/test_catalogue_limits.pf"
#line 29 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(7, s%nop, 'scheme table changed by the refused label '//trim(shown), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 29) )
  if (anyExceptions()) return
#line 30 "/work/wt10b/test/test_catalogue_limits.pf"
    end subroutine expect_refused

    !@test
    subroutine test_a46342_overflows_no_more()
        ! N (N - 2) overflows a default integer from N = 46342 on
        call expect_refused('A46342', FSYM_ERR_BAD_PARAMETER, '46342')
    end subroutine test_a46342_overflows_no_more

    !@test
    subroutine test_a1000000()
        call expect_refused('A1000000', FSYM_ERR_BAD_PARAMETER, '1000000')
    end subroutine test_a1000000

    !@test
    subroutine test_a99999999999_named_as_typed()
        ! more digits than any integer: reported with the digits typed, never as N = 0
        call expect_refused('A99999999999', FSYM_ERR_BAD_PARAMETER, '99999999999')
        call expect_refused('A2', FSYM_ERR_BAD_PARAMETER, 'N >= 3')
    end subroutine test_a99999999999_named_as_typed

    !@test
    subroutine test_billion_stage_an()
        ! a 1e9-stage table would need 20 GB: refused before any allocation
        type(scheme_t) :: s
        integer :: st
        character(len=200) :: msg
        call expect_refused('A500000001', FSYM_ERR_BAD_PARAMETER, '500000001')
        s = fsym_scheme_fr()
        call fsym_scheme_an(500000001, s, stat=st, errmsg=msg)
#line 59 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(FSYM_ERR_BAD_PARAMETER, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 59) )
  if (anyExceptions()) return
#line 60 "/work/wt10b/test/test_catalogue_limits.pf"
#line 60 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual('FR', s%name, &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 60) )
  if (anyExceptions()) return
#line 61 "/work/wt10b/test/test_catalogue_limits.pf"
        call fsym_scheme_an(huge(1), s, stat=st, errmsg=msg)
#line 62 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(FSYM_ERR_BAD_PARAMETER, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 62) )
  if (anyExceptions()) return
#line 63 "/work/wt10b/test/test_catalogue_limits.pf"
    end subroutine test_billion_stage_an

    !@test
    subroutine test_integrator_refuses_without_stopping()
        ! the same labels through the modern face: a status, the integrator still usable
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        integer :: st, k
        character(len=200) :: msg
        character(len=16), parameter :: labels(4) = [character(len=16) :: 'A46342', &
            'A1000000', 'A99999999999', 'A1000000000''']
        call it%init_by_name('A', kep, 2, 1, st, msg)
#line 75 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(FSYM_SUCCESS, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 75) )
  if (anyExceptions()) return
#line 76 "/work/wt10b/test/test_catalogue_limits.pf"
        do k = 1, size(labels)
            call it%init_by_name(trim(labels(k)), kep, 2, 1, st, msg)
#line 78 "/work/wt10b/test/test_catalogue_limits.pf"
  call assertEqual(FSYM_ERR_BAD_PARAMETER, st, trim(labels(k))//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_limits.pf', &
 & 78) )
  if (anyExceptions()) return
#line 79 "/work/wt10b/test/test_catalogue_limits.pf"
        end do
    end subroutine test_integrator_refuses_without_stopping

    !@test
    subroutine test_long_and_odd_labels()
        ! a label of a million characters, a parameter beyond the real range, an empty label
        character(len=:), allocatable :: long
        long = repeat('A', 1000000)
        call expect_refused(long, FSYM_ERR_UNKNOWN_METHOD, 'AAAA')
        call expect_refused('M2(-1e999)', FSYM_ERR_BAD_PARAMETER, '-1e999')
        call expect_refused('GFR5(1/0)', FSYM_ERR_BAD_PARAMETER, '1/0')
        call expect_refused('', FSYM_ERR_UNKNOWN_METHOD, 'known:')
    end subroutine test_long_and_odd_labels

end module test_catalogue_limits

module Wraptest_catalogue_limits
   use FUnit
   use test_catalogue_limits
   implicit none
   private

contains


end module Wraptest_catalogue_limits

function test_catalogue_limits_suite() result(suite)
   use FUnit
   use test_catalogue_limits
   use Wraptest_catalogue_limits
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_catalogue_limits_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_a46342_overflows_no_more', &
      test_a46342_overflows_no_more))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_a1000000', &
      test_a1000000))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_a99999999999_named_as_typed', &
      test_a99999999999_named_as_typed))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_billion_stage_an', &
      test_billion_stage_an))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_integrator_refuses_without_stopping', &
      test_integrator_refuses_without_stopping))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_long_and_odd_labels', &
      test_long_and_odd_labels))
   call suite%addTest(t)


end function test_catalogue_limits_suite

