!> Status codes returned by every public procedure, their messages, and the one place where
!> an error is reported to a caller (through `stat`/`errmsg`) or, if the caller asked for no
!> status, ends the program with the message.
!>
!> Thread-safe: no procedure here keeps state, and no character function result has a
!> deferred length (gfortran keeps the length of such a result in a static variable of the
!> caller, which threads would share). Texts come from constant tables; the functions that
!> return text have their exact length given by a specification function
!> (`fsym_status_message_len`, `fsym_int_text_len`), and `fsym_report` writes straight into
!> the caller's `errmsg`, allocating nothing.
module fsym_status
    use, intrinsic :: iso_fortran_env, only: error_unit
    use fsym_kinds, only: ik
    implicit none
    private

    integer, parameter, public :: FSYM_SUCCESS = 0
        !! No error.
    integer, parameter, public :: FSYM_ERR_UNKNOWN_METHOD = 1
        !! The method name is not in the catalogue.
    integer, parameter, public :: FSYM_ERR_BAD_PARAMETER = 2
        !! A family parameter is outside the family's domain.
    integer, parameter, public :: FSYM_ERR_INCONSISTENT_SCHEME = 3
        !! A user scheme violates consistency (drifts or kicks do not sum to one, bad op code).
    integer, parameter, public :: FSYM_ERR_BAD_STEP = 4
        !! The time step is zero, NaN or infinite.
    integer, parameter, public :: FSYM_ERR_NONFINITE_STATE = 5
        !! The state holds NaN or Inf (on entry, or the step would produce it).
    integer, parameter, public :: FSYM_ERR_NONFINITE_FORCE = 6
        !! The force model returned NaN or Inf.
    integer, parameter, public :: FSYM_ERR_SHAPE = 7
        !! Array shapes do not match the integrator's.
    integer, parameter, public :: FSYM_ERR_NO_GRADIENT = 8
        !! The scheme needs a gradient term that the force model does not provide.
    integer, parameter, public :: FSYM_ERR_NOT_INITIALIZED = 9
        !! The object was used before a successful `init`.
    integer, parameter, public :: FSYM_ERR_WORK_SIZE = 10
        !! A caller-provided work array is too short.
    integer, parameter, public :: FSYM_ERR_MODEL = 11
        !! The force model reported a failure through its own status.
    integer, parameter, public :: FSYM_ERR_NOT_ELLIPTIC = 12
        !! A Kepler helper was given an unbound or degenerate orbit.
    integer, parameter, public :: FSYM_ERR_NO_CONVERGENCE = 13
        !! An iteration (Kepler's equation, a root search) did not converge.
    integer, parameter, public :: FSYM_ERR_IO = 14
        !! Input/output failed (used by the programs, never by the core).
    integer, parameter, public :: FSYM_ERR_CAPACITY = 15
        !! A fixed-capacity buffer (e.g. a trace recorder) is full.
    integer, parameter, public :: FSYM_ERR_NO_POTENTIAL = 16
        !! A potential was asked of a force model that does not provide one.
    integer, parameter, public :: FSYM_ERR_BAD_REQUEST = 17
        !! Reverse communication was resumed out of order.
    integer, parameter, public :: FSYM_ERR_LAPACK = 18
        !! A LAPACK routine returned a non-zero info.
    integer, parameter, public :: FSYM_ERR_BAD_ARGUMENT = 19
        !! An argument is invalid: a step count <= 0, a NULL pointer from C, a label too long.
    integer, parameter, public :: FSYM_ERR_STEP_TOO_LARGE = 20
        !! The step-size guard refused a step: h omega beyond the method's stability limit.
    integer, parameter, public :: FSYM_ERR_CHECKPOINT = 21
        !! A checkpoint is corrupt, of another version, or does not fit this integrator.
    integer, parameter, public :: FSYM_ERR_CONVENTION = 22
        !! The F77 caller's integers are not default 4-byte integers (see FSYMCV).
    integer, parameter, public :: FSYM_ERR_NO_MEMORY = 23
        !! An allocation failed (e.g. a method table too large for memory).
    integer, parameter, public :: FSYM_ERR_BUSY = 24
        !! The object is in use: called again from inside its own call (a force model that
        !! steps the integrator that called it), or its work array was written meanwhile.
    integer, parameter, public :: FSYM_ERR_ENCOUNTER = 25
        !! Two bodies came within the encounter radius: the step was undone (the state as it
        !! was) and the message names the pair, for the host to hand over (planetary models).
    integer, parameter, public :: FSYM_ERR_LAST = 25
        !! Largest status code in use.
    integer, parameter, public :: FSYM_STATUS_MSG_LEN = 48
        !! Longest text of `fsym_status_message` (a buffer of this length always holds it).

    public :: fsym_status_message, fsym_status_message_len, fsym_report, fsym_pass
    public :: fsym_int_text, fsym_int_text_len, fsym_copy_printable

    !> The short text of each status code; the last entry is for unknown codes.
    character(len=FSYM_STATUS_MSG_LEN), parameter :: texts(0:FSYM_ERR_LAST + 1) = &
        [character(len=FSYM_STATUS_MSG_LEN) :: &
         'success', &
         'unknown method name', &
         'parameter outside the family''s domain', &
         'inconsistent scheme', &
         'time step is zero, NaN or infinite', &
         'state holds NaN or Inf', &
         'force model returned NaN or Inf', &
         'array shape mismatch', &
         'scheme needs a gradient the force model lacks', &
         'object used before a successful init', &
         'work array too short', &
         'force model reported a failure', &
         'orbit is not a bound ellipse', &
         'iteration did not converge', &
         'input/output error', &
         'buffer capacity exceeded', &
         'force model provides no potential', &
         'reverse communication resumed out of order', &
         'LAPACK routine failed', &
         'invalid argument', &
         'step too large for this orbit (guard)', &
         'checkpoint does not fit', &
         'caller integers are not 4-byte integers', &
         'out of memory', &
         'object busy: called from its own callback', &
         'close encounter: hand the pair over', &
         'unknown status code']

    !> Decimal text of an integer (default kind or `ik`), for messages and labels; its length
    !> is exactly the number of characters needed.
    interface fsym_int_text
        module procedure int_text_default, int_text_ik
    end interface fsym_int_text

    !> Number of characters of the decimal text of an integer (default kind or `ik`).
    interface fsym_int_text_len
        module procedure int_text_len_default, int_text_len_ik
    end interface fsym_int_text_len

contains

    !> Index of `code` in the table of texts.
    pure integer function text_index(code)
        integer, intent(in) :: code
        text_index = FSYM_ERR_LAST + 1
        if (code >= 0 .and. code <= FSYM_ERR_LAST) text_index = code
    end function text_index

    !> Length of `fsym_status_message(code)`.
    pure integer function fsym_status_message_len(code)
        integer, intent(in) :: code  !! a status code
        fsym_status_message_len = len_trim(texts(text_index(code)))
    end function fsym_status_message_len

    !> Short text for a status code ('unknown status code' for a code not in use).
    pure function fsym_status_message(code) result(msg)
        integer, intent(in) :: code  !! a status code
        character(len=fsym_status_message_len(code)) :: msg
        msg = texts(text_index(code))
    end function fsym_status_message

    !> Report an error: set `stat` and `errmsg` (`text: detail`, cut to the length of
    !> `errmsg`) when the caller passed them; when the caller passed no `stat`, the caller
    !> declined to handle errors, so write the message to standard error and stop. With
    !> code = FSYM_SUCCESS it only sets `stat` to zero. Allocates nothing.
    subroutine fsym_report(code, detail, stat, errmsg)
        integer, intent(in) :: code                            !! status code
        character(len=*), intent(in) :: detail                 !! what went wrong, in context
        integer, intent(out), optional :: stat                 !! receives `code`
        character(len=*), intent(inout), optional :: errmsg    !! receives the message on error
        integer :: n, m
        if (present(stat)) stat = code
        if (code == FSYM_SUCCESS) return
        n = len_trim(texts(text_index(code)))
        m = len_trim(detail)
        if (present(errmsg)) then
            errmsg = texts(text_index(code))
            if (m > 0 .and. n + 2 < len(errmsg)) then
                errmsg(n + 1:n + 2) = ': '
                errmsg(n + 3:) = detail(1:m)
            end if
        end if
        if (present(errmsg)) call make_printable(errmsg)
        if (.not. present(stat)) then
            if (m > 0) then
                write (error_unit, '(4a)') 'forward-symplectic: ', texts(text_index(code))(1:n), &
                    ': ', detail(1:m)
            else
                write (error_unit, '(2a)') 'forward-symplectic: ', texts(text_index(code))(1:n)
            end if
            error stop 1
        end if
    end subroutine fsym_report

    !> Hand on an error whose full text `msg` was produced by an inner call (as `fsym_report`
    !> does, but without adding the generic prefix again).
    subroutine fsym_pass(code, msg, stat, errmsg)
        integer, intent(in) :: code                            !! status code
        character(len=*), intent(in) :: msg                    !! full message from the inner call
        integer, intent(out), optional :: stat                 !! receives `code`
        character(len=*), intent(inout), optional :: errmsg    !! receives `msg` on error
        if (present(stat)) stat = code
        if (code == FSYM_SUCCESS) return
        if (present(errmsg)) call fsym_copy_printable(msg, errmsg)
        if (.not. present(stat)) then
            write (error_unit, '(2a)') 'forward-symplectic: ', trim(msg)
            error stop 1
        end if
    end subroutine fsym_pass

    !> Number of characters of the decimal text of a default integer.
    pure integer function int_text_len_default(k)
        integer, intent(in) :: k                  !! the integer
        int_text_len_default = int_text_len_ik(int(k, ik))
    end function int_text_len_default

    !> Number of characters of the decimal text of an integer(ik).
    pure integer function int_text_len_ik(k)
        integer(ik), intent(in) :: k              !! the integer
        integer(ik) :: a
        int_text_len_ik = 1
        if (k < 0_ik) int_text_len_ik = 2
        if (k == -huge(k) - 1_ik) then
            int_text_len_ik = 20; return          ! -9223372036854775808: no positive twin
        end if
        a = abs(k)
        do while (a >= 10_ik)
            a = a / 10_ik
            int_text_len_ik = int_text_len_ik + 1
        end do
    end function int_text_len_ik

    !> Copy a message, every byte outside printable ASCII (a user's label may hold any)
    !> replaced by '?', so that a message is always printable text.
    pure subroutine fsym_copy_printable(text, out)
        character(len=*), intent(in) :: text       !! the message
        character(len=*), intent(inout) :: out     !! receives it, blank-padded or cut
        out = text
        call make_printable(out)
    end subroutine fsym_copy_printable

    !> Replace, in place, every byte outside printable ASCII by '?'.
    pure subroutine make_printable(out)
        character(len=*), intent(inout) :: out     !! the text
        integer :: k
        do k = 1, len(out)
            if (iachar(out(k:k)) < 32 .or. iachar(out(k:k)) > 126) out(k:k) = '?'
        end do
    end subroutine make_printable

    !> Decimal text of a default integer.
    pure function int_text_default(k) result(s)
        integer, intent(in) :: k                  !! the integer
        character(len=int_text_len_default(k)) :: s
        write (s, '(i0)') k
    end function int_text_default

    !> Decimal text of an integer(ik).
    pure function int_text_ik(k) result(s)
        integer(ik), intent(in) :: k              !! the integer
        character(len=int_text_len_ik(k)) :: s
        write (s, '(i0)') k
    end function int_text_ik

end module fsym_status
