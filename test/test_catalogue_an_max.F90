!> The documented limits themselves: AN builds for every N up to `FSYM_AN_MAX` with drifts
!> and kicks summing to one and the evaluation counts of the family (N - 1 forces, one
!> gradient); N = `FSYM_AN_MAX` + 1 is refused; a label of `FSYM_LABEL_LEN` characters is
!> read, one more is refused as too long.
module test_catalogue_an_max
    use funit
    use fsym
    implicit none

contains

    !@test
    subroutine test_an_up_to_the_limit()
        type(scheme_t) :: s
        integer :: st, n
        character(len=200) :: msg
        character(len=12) :: label
        do n = FSYM_AN_MAX - 2, FSYM_AN_MAX
            write (label, '(a,i0)') 'A', n
            call fsym_scheme_by_name(label, s, st, msg)
#line 21 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(FSYM_SUCCESS, st, trim(label)//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 21) )
  if (anyExceptions()) return
#line 22 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 22 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(2 * n - 1, s%nop, trim(label), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 22) )
  if (anyExceptions()) return
#line 23 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 23 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(n - 1, s%nforce, trim(label), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 23) )
  if (anyExceptions()) return
#line 24 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 24 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(1, s%ngrad, trim(label), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 24) )
  if (anyExceptions()) return
#line 25 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 25 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(1.0_wp, sum(s%c, mask=(s%op == OP_DRIFT)), 1.0e-12_wp, trim(label), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 25) )
  if (anyExceptions()) return
#line 26 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 26 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(1.0_wp, sum(s%c, mask=(s%op /= OP_DRIFT)), 1.0e-12_wp, trim(label), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 26) )
  if (anyExceptions()) return
#line 27 "/work/wt10b/test/test_catalogue_an_max.pf"
        end do
        write (label, '(a,i0)') 'A', FSYM_AN_MAX + 1
        call fsym_scheme_by_name(label, s, st, msg)
#line 30 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(FSYM_ERR_BAD_PARAMETER, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 30) )
  if (anyExceptions()) return
#line 31 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 31 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual('A', s%name(1:1), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 31) )
  if (anyExceptions()) return
#line 32 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 32 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(2 * FSYM_AN_MAX - 1, s%nop, 'scheme changed by the refused label', &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 32) )
  if (anyExceptions()) return
#line 33 "/work/wt10b/test/test_catalogue_an_max.pf"
    end subroutine test_an_up_to_the_limit

    !@test
    subroutine test_label_length_limit()
        type(scheme_t) :: s
        integer :: st
        character(len=200) :: msg
        character(len=FSYM_LABEL_LEN) :: fits
        character(len=FSYM_LABEL_LEN + 1) :: too_long
        ! 'gfr5(1' + zeros + ')': exactly FSYM_LABEL_LEN characters, a valid label
        fits = 'gfr5(1.'//repeat('0', FSYM_LABEL_LEN - 8)//')'
        call fsym_scheme_by_name(fits, s, st, msg)
#line 45 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(FSYM_SUCCESS, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 45) )
  if (anyExceptions()) return
#line 46 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 46 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(fits, s%name, &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 46) )
  if (anyExceptions()) return
#line 47 "/work/wt10b/test/test_catalogue_an_max.pf"
        too_long = 'gfr5(1.'//repeat('0', FSYM_LABEL_LEN - 7)//')'
        call fsym_scheme_by_name(too_long, s, st, msg)
#line 49 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(FSYM_ERR_UNKNOWN_METHOD, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/wt10b/test/test_catalogue_an_max.pf"
#line 50 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertTrue(index(msg, 'longer than') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 50) )
  if (anyExceptions()) return
#line 51 "/work/wt10b/test/test_catalogue_an_max.pf"
        ! blanks do not count
        call fsym_scheme_by_name(' '//fits(1:5)//'   '//fits(6:), s, st, msg)
#line 53 "/work/wt10b/test/test_catalogue_an_max.pf"
  call assertEqual(FSYM_SUCCESS, st, trim(msg), &
 & location=SourceLocation( &
 & 'test_catalogue_an_max.pf', &
 & 53) )
  if (anyExceptions()) return
#line 54 "/work/wt10b/test/test_catalogue_an_max.pf"
    end subroutine test_label_length_limit

end module test_catalogue_an_max

module Wraptest_catalogue_an_max
   use FUnit
   use test_catalogue_an_max
   implicit none
   private

contains


end module Wraptest_catalogue_an_max

function test_catalogue_an_max_suite() result(suite)
   use FUnit
   use test_catalogue_an_max
   use Wraptest_catalogue_an_max
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_catalogue_an_max_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_an_up_to_the_limit', &
      test_an_up_to_the_limit))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_label_length_limit', &
      test_label_length_limit))
   call suite%addTest(t)


end function test_catalogue_an_max_suite

