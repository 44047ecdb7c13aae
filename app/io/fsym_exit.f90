!> How a program of app/ ends on a failure: one message on standard error and an exit status,
!> with no HDF5 (the HDF5 writer `fsym_h5` re-exports it), so that every program, with or
!> without HDF5, ends the same way.
module fsym_exit
    use, intrinsic :: iso_c_binding, only: c_int
    implicit none
    private

    public :: fsym_exit_failure

    interface
        subroutine c_exit_now(code) bind(C, name='_exit')
            import :: c_int
            implicit none
            integer(c_int), value :: code
        end subroutine c_exit_now
    end interface

contains

    !> End a program that failed: `program: text` on standard error, both standard units
    !> flushed (a buffered standard error that is a file would otherwise lose it), then exit
    !> status `code` (default 1) at once (`_exit`), without the exit handlers: after a write
    !> failed on a full disk, HDF5's own handler flushes the failed file again and crashes
    !> (SIGSEGV at exit, HDF5 1.10). Files the program writes must be closed or their
    !> temporaries removed before (every writer of `fsym_h5` does on failure).
    subroutine fsym_exit_failure(program, text, code)
        use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
        character(len=*), intent(in) :: program     !! program name
        character(len=*), intent(in) :: text        !! the message
        integer, intent(in), optional :: code       !! exit status (default 1)
        integer :: ios1, ios2, ios3, status
        status = 1
        if (present(code)) status = code
        ! each may fail on a full disk; nothing more can be done then, the exit status says it
        write (error_unit, '(a)', iostat=ios1) program//': '//trim(text)
        flush (output_unit, iostat=ios2)
        flush (error_unit, iostat=ios3)
        if (ios1 /= 0 .or. ios2 /= 0 .or. ios3 /= 0) continue
        call c_exit_now(int(status, c_int))
    end subroutine fsym_exit_failure

end module fsym_exit
