!> The unit-test harness of test/testing.f90 for the study tests in app/ (fpm lets only
!> sources in app/ use the study modules, and a test module there cannot use one in test/):
!> named test procedures, checks with tolerances, informational notes.
module fsym_study_testing
    use, intrinsic :: iso_fortran_env, only: output_unit
    use fsym_kinds, only: wp
    implicit none
    private

    public :: test_t, new_test, check, check_close, note, test_proc

    abstract interface
        !> A test: leaves `err` unallocated when it passes, else sets a message.
        subroutine test_proc(err)
            implicit none
            character(len=:), allocatable, intent(out) :: err
        end subroutine test_proc
    end interface

    !> A named test.
    type :: test_t
        character(len=:), allocatable :: name
        procedure(test_proc), pointer, nopass :: proc => null()
    end type test_t

contains

    !> A named test from a procedure.
    function new_test(name, proc) result(t)
        character(len=*), intent(in) :: name
        procedure(test_proc) :: proc
        type(test_t) :: t
        t%name = name
        t%proc => proc
    end function new_test

    !> Record a failure `msg` unless `cond` holds (the first failure is kept).
    subroutine check(err, cond, msg)
        character(len=:), allocatable, intent(inout) :: err
        logical, intent(in) :: cond
        character(len=*), intent(in) :: msg
        if (cond) return
        if (.not. allocated(err)) err = msg
    end subroutine check

    !> Check |actual - expected| <= tol, with both numbers in the message.
    subroutine check_close(err, actual, expected, tol, what)
        character(len=:), allocatable, intent(inout) :: err
        real(wp), intent(in) :: actual, expected, tol
        character(len=*), intent(in) :: what
        character(len=160) :: buf
        if (abs(actual - expected) <= tol) return
        write (buf, '(a,es12.5,a,es12.5,a,es9.2)') ': got ', actual, ', expected ', expected, &
            ', tol ', tol
        call check(err, .false., what//trim(buf))
    end subroutine check_close

    !> An informational line in the test output (measured values).
    subroutine note(text)
        character(len=*), intent(in) :: text
        write (output_unit, '(4x,a)') text
    end subroutine note

end module fsym_study_testing
