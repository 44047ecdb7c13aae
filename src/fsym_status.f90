!> Status codes returned by every public procedure, their messages, and the one place where
!> an error is reported to a caller (through `stat`/`errmsg`) or, if the caller asked for no
!> status, ends the program with the message.
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
    integer, parameter, public :: FSYM_ERR_LAST = 22
        !! Largest status code in use.

    public :: fsym_status_message, fsym_report, fsym_pass, fsym_int_text, fsym_copy_printable

    !> Decimal text of an integer (default kind or `ik`), for messages and labels.
    interface fsym_int_text
        module procedure int_text_default, int_text_ik
    end interface fsym_int_text

contains

    !> Short text for a status code.
    pure function fsym_status_message(code) result(msg)
        integer, intent(in) :: code  !! a status code
        character(len=:), allocatable :: msg
        select case (code)
        case (FSYM_SUCCESS);                 msg = 'success'
        case (FSYM_ERR_UNKNOWN_METHOD);      msg = 'unknown method name'
        case (FSYM_ERR_BAD_PARAMETER);       msg = 'parameter outside the family''s domain'
        case (FSYM_ERR_INCONSISTENT_SCHEME); msg = 'inconsistent scheme'
        case (FSYM_ERR_BAD_STEP);            msg = 'time step is zero, NaN or infinite'
        case (FSYM_ERR_NONFINITE_STATE);     msg = 'state holds NaN or Inf'
        case (FSYM_ERR_NONFINITE_FORCE);     msg = 'force model returned NaN or Inf'
        case (FSYM_ERR_SHAPE);               msg = 'array shape mismatch'
        case (FSYM_ERR_NO_GRADIENT);         msg = 'scheme needs a gradient the force model lacks'
        case (FSYM_ERR_NOT_INITIALIZED);     msg = 'object used before a successful init'
        case (FSYM_ERR_WORK_SIZE);           msg = 'work array too short'
        case (FSYM_ERR_MODEL);               msg = 'force model reported a failure'
        case (FSYM_ERR_NOT_ELLIPTIC);        msg = 'orbit is not a bound ellipse'
        case (FSYM_ERR_NO_CONVERGENCE);      msg = 'iteration did not converge'
        case (FSYM_ERR_IO);                  msg = 'input/output error'
        case (FSYM_ERR_CAPACITY);            msg = 'buffer capacity exceeded'
        case (FSYM_ERR_NO_POTENTIAL);        msg = 'force model provides no potential'
        case (FSYM_ERR_BAD_REQUEST);         msg = 'reverse communication resumed out of order'
        case (FSYM_ERR_LAPACK);              msg = 'LAPACK routine failed'
        case (FSYM_ERR_BAD_ARGUMENT);        msg = 'invalid argument'
        case (FSYM_ERR_STEP_TOO_LARGE);      msg = 'step too large for this orbit (guard)'
        case (FSYM_ERR_CHECKPOINT);          msg = 'checkpoint does not fit'
        case (FSYM_ERR_CONVENTION);          msg = 'caller integers are not 4-byte integers'
        case default;                        msg = 'unknown status code'
        end select
    end function fsym_status_message

    !> Report an error: set `stat` and `errmsg` when the caller passed them; when the caller
    !> passed no `stat`, the caller declined to handle errors, so write the message to
    !> standard error and stop. With code = FSYM_SUCCESS it only sets `stat` to zero.
    subroutine fsym_report(code, detail, stat, errmsg)
        integer, intent(in) :: code                            !! status code
        character(len=*), intent(in) :: detail                 !! what went wrong, in context
        integer, intent(out), optional :: stat                 !! receives `code`
        character(len=*), intent(inout), optional :: errmsg    !! receives the message on error
        character(len=:), allocatable :: text
        if (present(stat)) stat = code
        if (code == FSYM_SUCCESS) return
        if (len_trim(detail) > 0) then
            text = fsym_status_message(code)//': '//trim(detail)
        else
            text = fsym_status_message(code)
        end if
        if (present(errmsg)) call fsym_copy_printable(text, errmsg)
        if (.not. present(stat)) then
            write (error_unit, '(a)') 'forward-symplectic: '//text
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
            write (error_unit, '(a)') 'forward-symplectic: '//trim(msg)
            error stop 1
        end if
    end subroutine fsym_pass

    !> Copy a message, every byte outside printable ASCII (a user's label may hold any)
    !> replaced by '?', so that a message is always printable text.
    pure subroutine fsym_copy_printable(text, out)
        character(len=*), intent(in) :: text       !! the message
        character(len=*), intent(inout) :: out     !! receives it, blank-padded or cut
        integer :: k
        out = text
        do k = 1, min(len(text), len(out))
            if (iachar(out(k:k)) < 32 .or. iachar(out(k:k)) > 126) out(k:k) = '?'
        end do
    end subroutine fsym_copy_printable

    !> Decimal text of a default integer.
    pure function int_text_default(k) result(s)
        integer, intent(in) :: k                  !! the integer
        character(len=:), allocatable :: s
        character(len=12) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function int_text_default

    !> Decimal text of an integer(ik).
    pure function int_text_ik(k) result(s)
        integer(ik), intent(in) :: k              !! the integer
        character(len=:), allocatable :: s
        character(len=21) :: buf
        write (buf, '(i0)') k
        s = trim(buf)
    end function int_text_ik

end module fsym_status
