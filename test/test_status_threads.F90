!> Messages are thread-safe (issue 11, item 3): independent objects in OpenMP threads take
!> error paths at the same time (bad labels through the parser and the integrator, a zero
!> step, a NaN state, status texts, integer texts) and every thread gets exactly the text a
!> serial run gives. Compile this test with OpenMP (-fopenmp); the library itself is built
!> without it. Without OpenMP, or with one thread, the test fails: it would prove nothing.
module test_status_threads
    use funit
    use fsym
    !$ use omp_lib, only: omp_get_max_threads
    implicit none

    integer, parameter :: nlab = 8
    character(len=24), parameter :: labels(nlab) = [character(len=24) :: 'A2', 'Z9', &
        'M2(0.5)', 'GFR5(-1)', 'A46342', 'FR''', 'T2(1)', 'M1(t)']

contains

    !> The error text of each path for label k, case c (serial reference and thread body).
    subroutine error_paths(k, c, st, msg)
        integer, intent(in) :: k, c
        integer, intent(out) :: st
        character(len=*), intent(out) :: msg
        type(scheme_t) :: s
        type(integrator_t) :: it
        type(kepler_model_t) :: kep
        real(wp) :: q(2, 1), v(2, 1)
        msg = ''
        select case (c)
        case (0)
            call fsym_scheme_by_name(trim(labels(k)), s, st, msg)
        case (1)
            call it%init_by_name(trim(labels(k)), kep, 2, 1, st, msg)
        case (2)
            call it%init_by_name('A', kep, 2, 1, st, msg)
            q(:, 1) = [1.0_wp, 0.0_wp]; v(:, 1) = [0.0_wp, 1.0_wp]
            call it%step(kep, q, v, 0.0_wp, st, msg)
        case default
            call it%init_by_name('C', kep, 2, 1, st, msg)
            q(:, 1) = [real(k, wp), 0.0_wp]; v(:, 1) = [0.0_wp, 0.0_wp]
            q(2, 1) = q(2, 1) / 0.0_wp * 0.0_wp   ! NaN: a state that cannot be stepped
            call it%step(kep, q, v, 0.01_wp, st, msg)
        end select
    end subroutine error_paths

    !@test
    subroutine test_error_texts_in_threads()
        integer, parameter :: ncase = 4, nrep = 4000
        integer :: ref_st(nlab, 0:ncase - 1), st, k, c, i, bad, nthreads, code
        character(len=200) :: ref_msg(nlab, 0:ncase - 1), msg
        character(len=24) :: ref_int
        character(len=64) :: ref_text(0:FSYM_ERR_LAST + 2)
        nthreads = 1
        !$ nthreads = omp_get_max_threads()
#line 54 "/work/wt10b/test/test_status_threads.pf"
  call assertTrue(nthreads >= 2, 'needs OpenMP and at least 2 threads (OMP_NUM_THREADS)', &
 & location=SourceLocation( &
 & 'test_status_threads.pf', &
 & 54) )
  if (anyExceptions()) return
#line 55 "/work/wt10b/test/test_status_threads.pf"
        do c = 0, ncase - 1
            do k = 1, nlab
                call error_paths(k, c, ref_st(k, c), ref_msg(k, c))
#line 58 "/work/wt10b/test/test_status_threads.pf"
  call assertTrue(ref_st(k, c) /= FSYM_SUCCESS, 'not an error path: '//trim(labels(k)), &
 & location=SourceLocation( &
 & 'test_status_threads.pf', &
 & 58) )
  if (anyExceptions()) return
#line 59 "/work/wt10b/test/test_status_threads.pf"
            end do
        end do
        do code = 0, FSYM_ERR_LAST + 2
            ref_text(code) = fsym_status_message(code)
        end do
        bad = 0
        !$omp parallel do schedule(dynamic, 7) private(k, c, st, msg, code, ref_int) &
        !$omp reduction(+:bad)
        do i = 1, nrep * nlab
            k = mod(i, nlab) + 1
            c = mod(i / nlab, ncase)
            call error_paths(k, c, st, msg)
            if (st /= ref_st(k, c) .or. msg /= ref_msg(k, c)) bad = bad + 1
            code = mod(i, FSYM_ERR_LAST + 3)
            if (fsym_status_message(code) /= ref_text(code) .or. &
                len(fsym_status_message(code)) /= len_trim(ref_text(code))) bad = bad + 1
            write (ref_int, '(i0)') -i * 7919
            if (fsym_int_text(-i * 7919) /= trim(ref_int) .or. &
                len(fsym_int_text(-i * 7919)) /= len_trim(ref_int)) bad = bad + 1
        end do
        !$omp end parallel do
#line 80 "/work/wt10b/test/test_status_threads.pf"
  call assertEqual(0, bad, 'texts that differ from the serial run', &
 & location=SourceLocation( &
 & 'test_status_threads.pf', &
 & 80) )
  if (anyExceptions()) return
#line 81 "/work/wt10b/test/test_status_threads.pf"
    end subroutine test_error_texts_in_threads

end module test_status_threads

module Wraptest_status_threads
   use FUnit
   use test_status_threads
   implicit none
   private

contains


end module Wraptest_status_threads

function test_status_threads_suite() result(suite)
   use FUnit
   use test_status_threads
   use Wraptest_status_threads
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_status_threads_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_error_texts_in_threads', &
      test_error_texts_in_threads))
   call suite%addTest(t)


end function test_status_threads_suite

