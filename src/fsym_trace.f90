!> A recorder of force-evaluation points into buffers allocated once: (step, stage, kind,
!> position) per evaluation. Recording never allocates; when the buffer is full further
!> points are counted as dropped. Programs write the buffers out in slabs.
module fsym_trace
    use fsym_kinds, only: wp, ik
    use fsym_status
    use fsym_force, only: recorder_t
    implicit none
    private

    !> Fixed-capacity force-point trace.
    type, extends(recorder_t), public :: trace_recorder_t
        integer :: d = 0                          !! dimensions of a position
        integer :: n = 0                          !! particles per position
        integer :: count = 0                      !! points held
        integer(ik) :: dropped = 0                !! points that did not fit
        integer(ik), allocatable :: step(:)       !! step of each point
        integer, allocatable :: stage(:)          !! stage of each point
        integer, allocatable :: kind(:)           !! `EVAL_*` kind of each point
        real(wp), allocatable :: q(:, :, :)       !! positions (d, n, capacity)
    contains
        procedure :: init => trace_init                 !! allocate room for `capacity` points
        procedure :: record => trace_record             !! store one point (or count it as dropped)
        procedure :: clear => trace_clear               !! empty the buffer
    end type trace_recorder_t

contains

    !> Allocate room for `capacity` points of shape (d, n).
    subroutine trace_init(self, d, n, capacity, stat, errmsg)
        class(trace_recorder_t), intent(inout) :: self        !! the recorder
        integer, intent(in) :: d, n, capacity                 !! shape, capacity
        integer, intent(out), optional :: stat                !! status code
        character(len=*), intent(inout), optional :: errmsg   !! message on error
        integer :: ast
        if (d < 1 .or. n < 1 .or. capacity < 1) then
            call fsym_report(FSYM_ERR_SHAPE, 'trace needs d, n, capacity >= 1', stat, errmsg)
            return
        end if
        call trace_release(self)
        ! one allocation at a time: after a failure the rest are known to be unallocated
        allocate (self%step(capacity), stat=ast)
        if (ast == 0) allocate (self%stage(capacity), stat=ast)
        if (ast == 0) allocate (self%kind(capacity), stat=ast)
        if (ast == 0) allocate (self%q(d, n, capacity), stat=ast)
        if (ast /= 0) then
            call trace_release(self)
            call fsym_report(FSYM_ERR_NO_MEMORY, 'trace buffer for '// &
                             fsym_int_text(capacity)//' points', stat, errmsg)
            return
        end if
        self%d = d; self%n = n
        call self%clear()
        if (present(stat)) stat = FSYM_SUCCESS
    end subroutine trace_init

    !> Store one point (or count it as dropped when full or of the wrong shape).
    subroutine trace_record(self, step, stage, kind, q)
        class(trace_recorder_t), intent(inout) :: self  !! the recorder
        integer(ik), intent(in) :: step                 !! step number
        integer, intent(in) :: stage                    !! stage index
        integer, intent(in) :: kind                     !! `EVAL_*`
        real(wp), intent(in) :: q(:, :)                 !! position
        if (.not. allocated(self%step)) then
            self%dropped = self%dropped + 1; return
        end if
        if (self%count >= size(self%step) .or. size(q, 1) /= self%d .or. &
            size(q, 2) /= self%n) then
            self%dropped = self%dropped + 1; return
        end if
        self%count = self%count + 1
        self%step(self%count) = step
        self%stage(self%count) = stage
        self%kind(self%count) = kind
        self%q(:, :, self%count) = q
    end subroutine trace_record

    !> Empty the buffer (capacity kept).
    pure subroutine trace_clear(self)
        class(trace_recorder_t), intent(inout) :: self  !! the recorder
        self%count = 0
        self%dropped = 0
    end subroutine trace_clear

    !> Release whatever part of the buffers is allocated.
    subroutine trace_release(self)
        class(trace_recorder_t), intent(inout) :: self  !! the recorder
        if (allocated(self%step)) deallocate (self%step)
        if (allocated(self%stage)) deallocate (self%stage)
        if (allocated(self%kind)) deallocate (self%kind)
        if (allocated(self%q)) deallocate (self%q)
    end subroutine trace_release

end module fsym_trace
