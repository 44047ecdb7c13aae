!> Parameters of the per-method tests: a test case per method label, named by the label, so
!> that pFUnit (and CTest) report each method on its own. A `.pf` module extends the two
!> types (pFUnit wants its parameter and case types declared in the module it processes).
module fsym_test_methods
    use funit, only: AbstractTestParameter, ParameterizedTestCase
    use fsym, only: FSYM_NAME_LEN
    implicit none
    private
    public :: method_param_t, method_case_t

    !> One method label.
    type, extends(AbstractTestParameter) :: method_param_t
        character(len=FSYM_NAME_LEN) :: method = ''   !! method label, e.g. `A'` or `M2(-0.5)`
    contains
        procedure :: toString => method_param_string  !! the label, the case's name in reports
    end type method_param_t

    !> A test case that knows its method.
    type, extends(ParameterizedTestCase) :: method_case_t
        character(len=FSYM_NAME_LEN) :: method = ''   !! method label
    end type method_case_t

contains

    !> The label, trimmed: pFUnit names the case `test[label]`.
    function method_param_string(this) result(text)
        class(method_param_t), intent(in) :: this   !! the parameter
        character(len=:), allocatable :: text
        text = trim(this%method)
    end function method_param_string

end module fsym_test_methods
