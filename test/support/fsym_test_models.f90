!> Models used by several test modules.
module fsym_test_models
    use fsym, only: kepler_model_t
    implicit none
    private
    public :: wrapped_kepler_t

    !> The Kepler model without its fused stepper (`kepler_model_t%advance`): every step of
    !> the integrator then goes through the kernel with the model's force routines.
    type, extends(kepler_model_t) :: wrapped_kepler_t
    contains
        procedure :: has_advance => no_fused_stepper
    end type wrapped_kepler_t

contains

    !> False: the integrator does not call `advance`.
    logical function no_fused_stepper(self)
        class(wrapped_kepler_t), intent(in) :: self
        no_fused_stepper = .false.
    end function no_fused_stepper

end module fsym_test_models
